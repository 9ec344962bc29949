// WorldOperations.h — the robot-world functions the CBTL language binds as built-ins, as plain C++.
//
// Every function takes the calling thread's World (one per thread; it owns the Workspace, i.e. the mjData,
// and the FCL shapes) and, where it makes random choices, the caller's Rng. Frames: world coordinates;
// units: metres and radians. Predicates return bool (a failed precondition, such as an unknown object name,
// yields false); samplers return std::nullopt when their try budget is exhausted; actions return an
// ActionResult with an explicit status and leave the World in the action's final state (unchanged when the
// action fails). The signatures are listed for the language in docs/world.md.
#pragma once

#include "robot/world/Clearance.h"
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/Occlusion.h"
#include "robot/world/Workspace.h"

#include <optional>
#include <string>
#include <vector>

namespace cbtl::world {

// Per-thread state of the built-ins.
class World {
 public:
  explicit World(std::shared_ptr<const Scene> scene);
  Workspace& workspace() { return ws_; }
  const Workspace& workspace() const { return ws_; }
  const ClearanceChecker& clearance() const { return clearance_; }
  const std::optional<OcclusionSpec>& occlusion() const { return occlusion_; }
  // Everything the robot said, in order (the `say` action).
  std::vector<std::string>& utterances() { return utterances_; }

  IkOptions ik;          // used by the IK built-ins
  PlanOptions planning;  // used by the planning built-ins and actions

 private:
  Workspace ws_;
  ClearanceChecker clearance_;
  std::optional<OcclusionSpec> occlusion_;
  std::vector<std::string> utterances_;
};

namespace builtins {

// ---- poses and distances ---------------------------------------------------------------------------------
// `p` raised by `height` metres along world z, orientation unchanged.
Pose3 poseAbove(const Pose3& p, double height);
// The pose of `to` expressed in the frame of `from` (from⁻¹ ∘ to).
Pose3 relativePose(const Pose3& from, const Pose3& to);
// `a` ∘ `b`: b given in a's frame, returned in the world.
Pose3 composePose(const Pose3& a, const Pose3& b);
// Euclidean distance between the positions, metres.
double distance(const Pose3& a, const Pose3& b);
// Surface-to-surface distance between two movable objects placed at the given poses (0 when they
// overlap); -1 if a name is unknown.
double objectDistance(World& w, const std::string& a, const Pose3& poseA, const std::string& b, const Pose3& poseB);
// The current pose of a movable object, or nullopt for an unknown name.
std::optional<Pose3> objectPose(World& w, const std::string& object);
// The current tool_frame pose.
Pose3 toolPose(World& w);

// ---- collision and placement predicates ------------------------------------------------------------------
// The arm at q (current base, objects and held object) is within limits and collision-free.
bool collisionFreeConf(World& w, const ArmConfig& q);
// Two movable objects at the given poses do not intersect.
bool collisionFreePoses(World& w, const std::string& a, const Pose3& poseA, const std::string& b, const Pose3& poseB);
// `object` at `pose` is clear of the scenery and at least `clearance` metres from every other movable object.
bool placementClear(World& w, const std::string& object, const Pose3& pose, double clearance);

// ---- kinematics ------------------------------------------------------------------------------------------
// The tool_frame pose for q at the current base pose.
Pose3 forwardKinematics(World& w, const ArmConfig& q);
// Whether a collision-free IK solution reaching `tool` exists (first attempt seeded at the current arm).
bool ikFeasible(World& w, const Pose3& tool, Rng& rng);
// A collision-free IK solution for `tool`, seeded at a random configuration (so repeated calls spread over
// the solution set), or nullopt.
std::optional<ArmConfig> sampleIk(World& w, const Pose3& tool, Rng& rng);

// ---- samplers --------------------------------------------------------------------------------------------
// A pose for `object` resting on the top face of the box geom `surface`: uniform position over the face
// (inset so the object's footprint stays on it), uniform yaw, upright; the first of `tries` candidates that
// is placementClear with `clearance`, or nullopt.
std::optional<Pose3> samplePlacement(World& w, const std::string& object, const std::string& surface, double clearance,
                                     Rng& rng, int tries = 100);

// ---- perception ------------------------------------------------------------------------------------------
// Occlusion score (Occlusion.h) of the user's view with the arm at q; 0 in scenes without user_eyes.
double occlusion(World& w, const ArmConfig& q);

// ---- motion ----------------------------------------------------------------------------------------------
// Whether the arm can move from `from` to `to` without collision (RRTConnect within the World's budget).
bool motionFeasible(World& w, const ArmConfig& from, const ArmConfig& to, Rng& rng);

// ---- actions ---------------------------------------------------------------------------------------------
enum class ActionStatus {
  Done,
  InvalidArgument,  // unknown object or surface, or a value out of range
  NoPath,           // motion planning failed (details in ActionResult::detail)
  NoIk,             // no collision-free IK solution for the requested pose
  OutOfReach,       // the object is too far from the gripper to grasp
  NotHolding,       // the action needs a held object
  AlreadyHolding,   // grasp while holding something
  Blocked,          // the requested object placement collides
};

const char* toString(ActionStatus s);

struct ActionResult {
  ActionStatus status = ActionStatus::Done;
  std::string detail;
  std::vector<ArmConfig> armPath;  // executed arm waypoints, if the action moved the arm
  std::vector<Pose2> basePath;     // executed base waypoints, if the action moved the base
  bool done() const { return status == ActionStatus::Done; }
};

// Plans to `goal` and moves there.
ActionResult moveArm(World& w, const ArmConfig& goal, Rng& rng);
// Solves collision-free IK for the tool pose (seeded at the current arm), then plans and moves.
ActionResult moveArmToPose(World& w, const Pose3& tool, Rng& rng);
// Plans the mobile base to `goal` (arm fixed) and moves there.
ActionResult moveBase(World& w, const Pose2& goal, Rng& rng);
// Attaches `object` to the gripper at its current relative pose and closes the gripper; the object's
// origin must be within `maxDistance` metres of the finger tip.
ActionResult grasp(World& w, const std::string& object, double maxDistance = 0.15);
// Detaches the held object where it is and opens the gripper.
ActionResult release(World& w);
// Slides a movable object (the plate, the drink) to (x, y) keeping its height and orientation, as the
// caregiver does in the feeding domain; Blocked if it would intersect scenery or other objects.
ActionResult moveObjectTo(World& w, const std::string& object, double x, double y);
ActionResult movePlate(World& w, double x, double y);
ActionResult moveDrink(World& w, double x, double y);
// Carries the held object to `position` with the fixed handover orientation rpy(-π/4, π/2, 0) of the tool,
// then says "Here you go!".
ActionResult handOver(World& w, const Eigen::Vector3d& position, Rng& rng);
// Wipes the top face of the box geom `surface` with the held tool: a boustrophedon of ceil(width / 0.15 m)
// passes along the face's longer side, the tool pointing down `toolHeight` metres above the face. Moves
// between waypoints by straight joint-space segments when they are free, otherwise by planning.
ActionResult wipe(World& w, const std::string& surface, Rng& rng, double toolHeight = 0.3);
// Records an utterance of the robot.
ActionResult say(World& w, const std::string& text);

}  // namespace builtins
}  // namespace cbtl::world
