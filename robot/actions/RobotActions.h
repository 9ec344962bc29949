// RobotActions.h — the executor of std.actions (stdlib/std/actions.cbtl) on a robot world, shared by the
// home-scene domains (Cleaning, Books) and Feeding. Domain-only actions (Feeding's movePlate) are the domain's.
//
// execute(world, call, rng) runs one sim::ActionCall whose name is a standard action and returns what
// happened; for any other name it returns std::nullopt, so a domain handles its own actions first or after.
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
//   moveArmToNamed(name)        moveArm to the scene's named configuration (NamedConfigurations.h, as std.kinova's
//                               namedConf); an unknown name fails (InvalidArgument, the detail lists the known
//                               names).
//   moveBase(pose: SE2)         plan the base in SE(2) with the arm fixed and move there.
//   grasp(body)                 fails AlreadyHolding / InvalidArgument (unknown body). A body with a standard
//                               grasp (StandardGrasps.h: the duster) is approached first unless the tool is
//                               already within 1 cm / 0.1 rad of that grasp; other bodies must be between the
//                               fingers already (finger tip within 0.15 m of the body's origin, OutOfReach
//                               otherwise). Then the gripper closes, the body is attached at its current
//                               relative pose, and the tool lifts kLift straight up (NoIk / NoPath if not).
//   closeGripper(closure)       gripper opening = 1 - closure, closure in [0, 1] (InvalidArgument outside);
//                               attaches nothing and drops nothing.
//   release()                   NotHolding if empty-handed. The body must land: its bottom within kDropHeight
//                               above a resting surface (SurfaceGeometry.h restingSurfaces) whose face holds
//                               its footprint; it is then settled onto that face with the gripper open.
//                               Blocked (nothing released) when it would fall elsewhere.
//   place(surface, pose: SE3)   NotHolding; InvalidArgument (unknown surface, or `pose` does not rest on it:
//                               SurfaceGeometry.h restsOn); Blocked (the body at `pose` would penetrate the
//                               scenery or another object). Moves the tool to pose ∘ inverse(toolToObject)
//                               unless it is already within 1 mm / 0.01 rad of it, releases the body settled
//                               exactly at `pose` (z snapped onto the face), opens the gripper and retracts the
//                               tool kRetract along its -z (NoIk / NoPath if that is impossible).
//   handOver()                  NotHolding if empty-handed; otherwise holds the object out where the tool is
//                               and says "Here you go!". Whether the user takes it is the domain's business.
//   wipe(surface, base: SE2)    WipeSweep.h sweepSurface.
//   say(utterance)              recorded in World::utterances().
//   waitForUser(signal)         nothing happens in the world; domains with a user interpret the signal.
//   wait(n)                     n steps pass (InvalidArgument for a negative or fractional n).
#pragma once

#include "robot/world/WorldOperations.h"
#include "runtime/sim/DomainSimulator.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::actions {

inline constexpr double kLift = 0.01;        // metres the tool rises after a grasp
inline constexpr double kRetract = 0.05;     // metres the tool backs off along its -z after a place
inline constexpr double kDropHeight = 0.03;  // metres a released body may fall onto a surface

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

class RobotActions {
 public:
  static bool isStandard(std::string_view name);

  // Runs `call` on `w` drawing random choices from `rng`; nullopt when `call.name` is not a standard action.
  std::optional<RobotActionResult> execute(world::World& w, const sim::ActionCall& call, world::Rng& rng) const;

 private:
  RobotActionResult grasp(world::World& w, const std::string& body, world::Rng& rng) const;
  RobotActionResult release(world::World& w) const;
  RobotActionResult place(world::World& w, const std::string& surface, const world::Pose3& pose, world::Rng& rng) const;
};

}  // namespace cbtl::actions
