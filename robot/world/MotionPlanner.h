// MotionPlanner.h — collision-free motion planning for the arm (joint space) and the mobile base (SE(2))
// with OMPL's RRTConnect, followed by shortcutting.
//
// Spaces: the arm space is SO(2) for the continuous joints 1, 3, 5, 7 and bounded R for joints 2, 4, 6; the
// base space is R x R x SO(2) (x, y in metres within `baseBounds`, yaw) with the arm held at its current
// joints. States are valid when the robot (and held object) is collision-free (Collision.h) and joints are
// within limits; edges, the straight segment tried first and every shortcut are accepted only when certified
// free along their whole length (SegmentCertificate.h), so a plan's path is free between its waypoints too.
// Determinism: a plan depends only on its inputs and the state of the Rng passed in, never on what the
// process planned before. Every random choice comes from that Rng: each planning call draws one word from it
// to seed the state sampler that replaces OMPL's (all sampler instances of one call share that seed; uniform,
// near and Gaussian draws are rt::Rng's), and shortcutting draws from the Rng itself. OMPL's own generators
// (ompl::RNG members of StateSampler and RRTConnect, each seeded from OMPL's process-wide seed sequence, so
// dependent on how many were created before) are never drawn from on this path: the samplers are ours,
// RRTConnect draws only through its sampler, a single goal state is copied rather than sampled, and
// nearest-neighbour search is exhaustive (NearestNeighborsLinear; GNAT would draw from OMPL's RNG). OMPL's
// process-wide seed is still fixed (1, once, before any planner exists) so that a future OMPL version that
// does draw internally is at least repeatable per process; OMPL logging is reduced to warnings.
// Budgets are RRTConnect iterations, never wall-clock time.
// Thread safety: the planner functions use only the Workspace passed in; call them concurrently with
// one Workspace per thread.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/JointPath.h"
#include "robot/world/Workspace.h"

#include <vector>

namespace cbtl::world {

enum class PlanStatus {
  Solved,
  InvalidStart,     // the start state is in collision or out of limits
  InvalidGoal,      // the goal state is in collision or out of limits
  BudgetExhausted,  // no path found within maxIterations
  NoMobileBase,     // base planning requested in a scene without a mobile base
};

const char* toString(PlanStatus s);

struct PlanOptions {
  int maxIterations = 20000;   // RRTConnect iterations
  int shortcutAttempts = 60;   // random shortcuts after planning (0: greedy vertex pruning only)
  double range = 0.0;          // RRTConnect step (L1 over coordinates); 0: OMPL's default
  bool tryDirectFirst = true;  // check the straight segment before running RRTConnect
  // Base planning bounds (x_lo, x_hi, y_lo, y_hi); if lo >= hi, the box spanning start and goal grown by
  // 0.5 m is used.
  double baseBounds[4] = {0, 0, 0, 0};
  CollisionOptions collision;
};

struct ArmPlan {
  PlanStatus status = PlanStatus::BudgetExhausted;
  std::vector<ArmConfig> path;  // start ... goal (vertices; consecutive ones connect by interpolation)
  int iterations = 0;           // RRTConnect iterations (0 when the straight segment was free)
  long validityChecks = 0;      // states checked (sampled states and the states certification evaluated)
  double length = 0.0;          // sum of |Δq| over joints and segments, rad
  bool solved() const { return status == PlanStatus::Solved; }
};

struct BasePlan {
  PlanStatus status = PlanStatus::BudgetExhausted;
  std::vector<Pose2> path;
  int iterations = 0;
  long validityChecks = 0;
  bool solved() const { return status == PlanStatus::Solved; }
};

// Plans the arm from start to goal with the Workspace's base, objects and held object. The Workspace's arm
// is left at `start`.
ArmPlan planArm(Workspace& ws, const ArmConfig& start, const ArmConfig& goal, Rng& rng,
                const PlanOptions& options = {});

// Plans the mobile base from its pose in the Workspace to `goal`, arm fixed at its current joints. The base
// is left at the start pose.
BasePlan planBase(Workspace& ws, const Pose2& goal, Rng& rng, const PlanOptions& options = {});

// The joint space of the arm (continuous joints circular).
JointSpace armSpace(const Scene& scene);
// Whether the straight joint-space segment a→b is within limits and certified free (SegmentCertificate.h), ends
// included. Adds the states it evaluated to *states. Leaves the arm at an unspecified configuration of the segment.
bool armSegmentFree(Workspace& ws, const ArmConfig& a, const ArmConfig& b, const CollisionOptions& options = {},
                    long* states = nullptr);

}  // namespace cbtl::world
