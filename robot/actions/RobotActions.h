// RobotActions.h — the executor of std.actions (stdlib/std/actions.cbtl) on a robot world, shared by the
// home-scene domains (Cleaning, Books) and Feeding. Domain-only actions (Feeding's movePlate) are the domain's.
//
// execute(world, call, mode) runs one sim::ActionCall: the domain's own actions first (DomainActions, given at
// construction: Feeding's movePlate, ...), then the standard ones; for any other name it returns std::nullopt.
// The same executor serves the domain's simulator (which carries plans out) and the runtime's world model
// (which dry-runs candidate plans before accepting them, robot/bind/WorldHost.h), so a plan the dry run
// accepted is one the simulator carries out from the same state.
//
// Pure: an action's outcome is a function of the world state and the call. Its random choices (IK restarts,
// the planner's stream) are seeded from a fingerprint of both (world/MotionQuery.h), never from a caller's
// generator, and its motions go through the scene's motion cache.
//
// Modes (ExecutionMode):
//   Execute  every check, planned motions: what the robot does.
//   Effects  only the end state the action leaves when it succeeds, for state progression between skills:
//            motions teleport (no path is planned, no configuration on the way is checked), IK that decides an
//            end configuration still runs, preconditions that decide whether the end state is defined still
//            apply (holding, unknown names, a body within reach of the fingers, a placement that rests on its
//            surface); the wiping sweep is not checked. Much cheaper than Execute; when Execute succeeds both
//            leave the same state.
//
// It never throws for bad input from a plan:
//   - a call of the wrong shape (argument count, kind, vector length) is `wellFormed == false` (the simulator
//     reports sim::ActionStatus::UnknownAction); the world is unchanged and no step passes;
//   - a well-formed call the world cannot carry out (no IK, no path, unknown body or named configuration,
//     NaN values, ...) fails with an explicit world::builtins::ActionStatus and detail; the world is left
//     exactly as before the call.
//
// Steps: every well-formed action takes one simulator step, whether it succeeds or fails (the robot spent
// the time trying), except wait(n), which takes n steps (n a whole number >= 0; wait(0) takes none).
//
// Actions (world frame, metres, radians; value layouts in CallArguments.h):
//   moveArm(q: Conf)            plan (straight segment first, then RRTConnect) and move the arm to q.
//   moveTool(tool: SE3)         IK seeded at the current joints, then as moveArm. Simplification: a joint-space
//                               move to the IK solution, not a Cartesian servo.
//   moveToolStraight(tool: SE3) the tool frame along the straight line to `tool` (world/CartesianPath.h: 1 cm /
//                               0.05 rad steps, IK seeded at the previous step, each joint segment certified);
//                               NoPath when no such line exists (never a joint-space detour). Effects mode
//                               follows the same IK chain without collision checks.
//   moveArmToNamed(name)        moveArm to the scene's named configuration (NamedConfigurations.h, as std.kinova's
//                               namedConf); an unknown name fails (InvalidArgument, the detail lists the known
//                               names).
//   moveBase(pose: SE2)         plan the base in SE(2) with the arm fixed and move there.
//   grasp(body)                 fails AlreadyHolding / InvalidArgument (unknown body). A body with standard
//                               grasps (StandardGrasps.h: the duster) is grasped where the tool is when it is
//                               within 1 cm / 0.1 rad of one of them, else grasp 0 is approached first; other
//                               bodies must be between the fingers already (finger tip within 0.15 m of the
//                               body's origin, OutOfReach otherwise). Then the fingers close until both touch the
//                               body (world/GraspClosure.h: pads pressed kGraspSqueeze in, the body pushed to the
//                               centre by at most kGraspMaxPush; NoGrip when they would close on air or the open
//                               gripper overlaps it), the body is attached at its relative pose, and the tool
//                               lifts kLift straight up (NoIk / NoPath if not).
//   closeGripper(closure)       gripper opening = 1 - closure, closure in [0, 1] (InvalidArgument outside);
//                               attaches nothing and drops nothing. Blocked (nothing changes) when the fingers
//                               would touch the world or sink into a held body beyond kGraspCompliance.
//   release()                   NotHolding if empty-handed. The body must land: its bottom within kDropHeight
//                               above a resting surface (SurfaceGeometry.h restingSurfaces) whose face holds
//                               its footprint; it is then settled onto that face with the gripper open.
//                               Without such a face, whatever is under its footprint within kDropHeight catches
//                               it (world/Support.h dropDistance: a round table top) if it then stands
//                               supported there (supportAt). Blocked (nothing released) when it would fall
//                               elsewhere.
//   place(surface, pose: SE3)   NotHolding; InvalidArgument (unknown surface, or `pose` does not rest on it:
//                               SurfaceGeometry.h restsOn); Blocked (the body at `pose` would penetrate the
//                               scenery or another object). Moves the tool to pose ∘ inverse(toolToObject)
//                               unless it is already within 1 mm / 0.01 rad of it, releases the body settled
//                               exactly at `pose` (z snapped onto the face), opens the gripper and retracts the
//                               tool kRetract along its -z (NoIk / NoPath if that is impossible).
//   handOver()                  NotHolding if empty-handed; Blocked when the gripper could not open where it
//                               is (an open finger would touch the scenery or the user: the user may take the
//                               object, and the gripper opens to let go). Otherwise holds the object out where
//                               the tool is and says "Here you go!". Whether the user takes it is the domain's
//                               business.
//   wipe(surface, base: SE2)    WipeSweep.h sweepSurface.
//   say(utterance)              recorded in World::utterances().
//   waitForUser(signal)         nothing happens in the world; domains with a user interpret the signal.
//   wait(n)                     n steps pass (InvalidArgument for a negative or fractional n).
#pragma once

#include "robot/world/WorldOperations.h"
#include "runtime/sim/DomainSimulator.h"

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::actions {

inline constexpr double kLift = 0.01;        // metres the tool rises after a grasp
inline constexpr double kRetract = 0.05;     // metres the tool backs off along its -z after a place
inline constexpr double kDropHeight = 0.03;  // metres a released body may fall onto a surface
// Metres a held body may sink into the surface it is lifted from or placed on (contact compliance): the only
// contact grasp and place allow their motions (world/Collision.h ContactAllowance).
inline constexpr double kRestingContact = 0.001;

struct RobotActionResult {
  bool wellFormed = true;  // false: the call does not fit its declaration (detail says why)
  world::builtins::ActionStatus status = world::builtins::ActionStatus::Done;
  std::string detail;                     // why it failed, or what it did when that is worth saying
  int steps = 1;                          // simulator steps the action took (0 for an ill-formed call)
  std::vector<world::ArmConfig> armPath;  // executed arm waypoints, when the arm moved
  std::vector<world::Pose2> basePath;     // executed base waypoints, when the base moved

  bool done() const { return wellFormed && status == world::builtins::ActionStatus::Done; }
  bool consumedStep() const { return steps > 0; }
  // Applied when done, Ignored when it failed, UnknownAction when ill-formed.
  sim::ActionStatus simStatus() const;
  // A sim::StepResult with the status, consumedStep and a message ("<action>: <status>: <detail>").
  sim::StepResult toStepResult(const std::string& action) const;
};

enum class ExecutionMode { Execute, Effects };

// A domain's own actions on the robot world (domains/<name>/): executed before the standard ones, with the
// contract above (pure, both modes, nothing thrown, the world unchanged on failure).
class DomainActions {
 public:
  virtual ~DomainActions() = default;
  // nullopt: `call` is not one of the domain's actions.
  virtual std::optional<RobotActionResult> execute(world::World& w, const sim::ActionCall& call,
                                                   ExecutionMode mode) const = 0;
  // Whether `name` is one of the domain's actions.
  virtual bool handles(std::string_view name) const = 0;
};

class RobotActions {
 public:
  explicit RobotActions(std::shared_ptr<const DomainActions> domain = nullptr) : domain_(std::move(domain)) {}

  static bool isStandard(std::string_view name);
  // A standard action or one of the domain's.
  bool knows(std::string_view name) const { return isStandard(name) || (domain_ && domain_->handles(name)); }

  // Runs `call` on `w`; nullopt when `call.name` is neither the domain's nor a standard action.
  std::optional<RobotActionResult> execute(world::World& w, const sim::ActionCall& call,
                                           ExecutionMode mode = ExecutionMode::Execute) const;

 private:
  RobotActionResult standard(world::World& w, const sim::ActionCall& call, ExecutionMode mode) const;
  RobotActionResult grasp(world::World& w, const std::string& body, ExecutionMode mode) const;
  RobotActionResult release(world::World& w) const;
  RobotActionResult closeGripper(world::World& w, double closure) const;
  RobotActionResult handOver(world::World& w) const;
  RobotActionResult place(world::World& w, const std::string& surface, const world::Pose3& pose,
                          ExecutionMode mode) const;

  std::shared_ptr<const DomainActions> domain_;
};

// Moves the arm to q: in Execute mode world::builtins::moveArm (planned, cached); in Effects mode it teleports
// (q must be finite and within limits). For domain actions built on the standard motions.
world::builtins::ActionResult moveArmIn(world::World& w, const world::ArmConfig& q, ExecutionMode mode);
// The contacts a lift may start in: each geom the held object touches now (within kRestingContact: the surface it is
// lifted from) may be touched by it up to kRestingContact deep. Empty when nothing is held.
std::vector<world::ContactAllowance> restingContacts(world::World& w);
// Moves the tool to `target` from the current joints: IK seeded there (so the arm stays in its branch; restarts
// seeded from the state and target), then moveArmIn.
world::builtins::ActionResult moveToolIn(world::World& w, const world::Pose3& target, ExecutionMode mode);
// Moves the tool along the straight line to `target` (world/CartesianPath.h), or fails NoPath: never a joint-space
// detour. Effects mode follows the same IK chain without collision checks.
world::builtins::ActionResult moveToolStraightIn(world::World& w, const world::Pose3& target, ExecutionMode mode);

}  // namespace cbtl::actions
