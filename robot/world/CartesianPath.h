// CartesianPath.h — the tool frame moved along a straight line in Cartesian space (a short approach into a
// shelf, a lift, a retreat), joint configurations found step by step.
//
// Why: a straight segment in joint space between two IK solutions 8 cm apart bows away from the Cartesian line,
// and in a narrow place (an open finger a millimetre from a shelf's side support) it touches what the line
// itself never comes near. The planner then has to find a way through a passage a few millimetres wide, which
// RRTConnect rarely does within its budget. Following the line is what a tool motion means.
//
// Contract: positions are interpolated linearly and orientations by slerp, in at most `maxStep` metres and
// `maxAngle` radians per step (world frame). Each step's configuration is IK seeded at the previous one (one
// attempt, no random restart, collision-free with `collision`), must lie within `maxJointStep` radians (L∞) of
// it, and the joint segment between the two must be certified free with `collision` (SegmentCertificate.h). The result
// starts at the current configuration and ends at an IK solution of `target`; the Workspace is left in the
// state it had. Deterministic: no random draws, so the answer is cached in the scene's MotionCache (MotionQuery.h,
// kind Line) and the executor's line after a dry run's is a lookup.
#pragma once

#include "robot/world/InverseKinematics.h"
#include "robot/world/Workspace.h"

#include <optional>
#include <vector>

namespace cbtl::world {

struct CartesianPathOptions {
  double maxStep = 0.01;       // m of tool travel per step
  double maxAngle = 0.05;      // rad of tool rotation per step
  double maxJointStep = 0.25;  // rad (L∞) between consecutive configurations: larger is a branch jump
  int maxSteps = 500;          // a longer move takes larger steps (bounded work; the joint checks still hold)
  CollisionOptions collision;
  // false: no collision check at all (IK steps and joint segments), for an end state only (an executor's Effects
  // mode). The configurations are the same as with the checks, which only decide whether the line is accepted.
  bool checkCollisions = true;
};

// The waypoints (current configuration first), or nullopt when some step has no collision-free IK near the
// previous configuration or its joint segment collides.
std::optional<std::vector<ArmConfig>> cartesianToolPath(Workspace& ws, const Pose3& target, const IkOptions& ik,
                                                        const CartesianPathOptions& options = {});

}  // namespace cbtl::world
