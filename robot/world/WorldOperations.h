// WorldOperations.h — the operations on a robot world that the robot domains' simulators and the action
// executor (robot/actions/RobotActions.h) build on, as plain C++.
//
// Every function takes the calling thread's World (one per thread; it owns the Workspace, i.e. the mjData,
// and the FCL shapes) and, where it makes random choices, the caller's Rng. Frames: world coordinates;
// units: metres and radians. Predicates return bool (a failed precondition, such as an unknown object name,
// yields false); samplers return std::nullopt when their try budget is exhausted; actions return an
// ActionResult with an explicit status and leave the World in the action's final state (unchanged when the
// action fails). The language's built-ins are robot/bind's (WorldBuiltins.h), not these.
#pragma once

#include "robot/world/Clearance.h"
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/MotionRecord.h"
#include "robot/world/Occlusion.h"
#include "robot/world/Workspace.h"

#include <optional>
#include <string>
#include <utility>
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

  // The record of what the robot did (MotionRecord.h): while recording is on, the executors note every motion
  // they carry out, with the contacts allowed for it. The simulators' worlds record; a dry run's world never does.
  void setRecording(bool on) { recording_ = on; }
  bool recording() const { return recording_; }
  // `path` starts at the configuration the arm (base) moved from; the rest of the world is the Workspace's now.
  void noteArmMotion(const std::vector<ArmConfig>& path, const CollisionOptions& collision);
  void noteBaseMotion(const std::vector<Pose2>& path, const CollisionOptions& collision);
  // The motions noted since the last call.
  std::vector<ExecutedMotion> takeMotions() { return std::exchange(motions_, {}); }

 private:
  Workspace ws_;
  ClearanceChecker clearance_;
  std::optional<OcclusionSpec> occlusion_;
  std::vector<std::string> utterances_;
  bool recording_ = false;
  std::vector<ExecutedMotion> motions_;
};

namespace builtins {

// ---- placement ------------------------------------------------------------------------------------------
// `object` at `pose` is clear of the scenery and at least `clearance` metres from every other movable object.
bool placementClear(World& w, const std::string& object, const Pose3& pose, double clearance);

// ---- kinematics ------------------------------------------------------------------------------------------
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
  NoGrip,           // the fingers would not hold the object (GraspClosure.h: closes on air, blocked, off centre)
};

const char* toString(ActionStatus s);

struct ActionResult {
  ActionStatus status = ActionStatus::Done;
  std::string detail;
  std::vector<ArmConfig> armPath;  // executed arm waypoints, if the action moved the arm
  std::vector<Pose2> basePath;     // executed base waypoints, if the action moved the base
  bool done() const { return status == ActionStatus::Done; }
};

// Plans to `goal` and moves there (MotionQuery.h planArmCached: straight segment first, then RRTConnect with
// w.planning; the plan is a pure function of the world state and `goal`, shared through the scene's cache).
ActionResult moveArm(World& w, const ArmConfig& goal);
// Plans the mobile base to `goal` (arm fixed) and moves there (planBaseCached, likewise pure).
ActionResult moveBase(World& w, const Pose2& goal);
// Closes the gripper on `object` (GraspClosure.h: the fingers stop where they touch it, pushing it to the centre by
// at most kGraspMaxPush) and attaches it at its relative pose then; the object's origin must be within `maxDistance`
// metres of the finger tip. Fails NoGrip (the world unchanged) when the fingers would close on air or the open
// gripper already overlaps the object. The closing itself is not checked against the rest of the world: the
// motion that follows (a lift) starts in the closed state and is certified.
ActionResult grasp(World& w, const std::string& object, double maxDistance = 0.15);
// Detaches the held object where it is and opens the gripper.
ActionResult release(World& w);
// Records an utterance of the robot.
ActionResult say(World& w, const std::string& text);

}  // namespace builtins
}  // namespace cbtl::world
