// MotionQuery.h — a motion-planning query as data (what is planned, from which world state, with which
// options), its 64-bit fingerprint, and a cache of answers keyed by it.
//
// Why: the planners (MotionPlanner.h) are made pure functions of their query — the planner's random stream is
// seeded from the query's fingerprint, never from a caller's generator — so the same query gives the same
// answer wherever it is asked: in the runtime's dry run of a candidate plan, in the executor that carries the
// plan out, in a resumed run. A cached answer therefore equals a fresh one, and caching changes speed, never
// results (tests: WorldMotionCache.*).
//
// The key is every input of the plan, as the exact bits of its doubles: the kind (arm or base), the start (arm
// joints and base pose), the goal, the gripper opening, the held object and its grasp, every movable object's
// and every fixture's pose, and the options that shape the result (shortcut attempts, RRTConnect range,
// direct-segment first, the contact allowances, base bounds). The iteration budget is *not* in the key: with
// the random stream fixed by the key, RRTConnect explores the same tree whatever its budget, so a plan found at
// iteration k is found by every budget >= k, and a failure with budget B answers every budget <= B. An entry
// records which budget it was computed with, and a lookup with a larger budget than a failed entry's plans
// again (continuing the same stream from its start).
//
// The cache belongs to the Scene (Scene::motionCache()), so everything that plans in one loaded scene — the
// program's world built-ins, the training and evaluation simulators — shares it without any wiring.
// Thread safety: every member function locks (simulators of one scene may run on several threads). Capacity:
// entries beyond `capacity` evict the oldest (first in, first out), which again changes only speed. Two
// queries with one fingerprint (never seen; 64 bits) are told apart by their keys: the newer replaces the
// older.
#pragma once

#include "robot/world/MotionPlanner.h"

#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

namespace cbtl::world {

// Arm and Base: planArm / planBase. Line: a Cartesian tool line (CartesianPath.h), deterministic without a random
// stream (one IK attempt per step, seeded at the previous step).
enum class MotionKind : std::uint8_t { Arm, Base, Line };

struct MotionQuery {
  MotionKind kind = MotionKind::Arm;
  std::vector<double> key;  // every input of the plan but the budget (see above), as doubles
  std::uint64_t fingerprint = 0;
};

// The query for planning the arm to `goal` (kind Arm) or the base to `goal` (kind Base, `goal` = x, y, yaw)
// from the Workspace's current state with `options`.
MotionQuery armQuery(const Workspace& ws, const ArmConfig& goal, const PlanOptions& options);
MotionQuery baseQuery(const Workspace& ws, const Pose2& goal, const PlanOptions& options);
// The query for a Cartesian tool line to `target` from the Workspace's current state: `collision`, the line's own
// options and the IK options its steps use, as numbers (`lineOptions`, CartesianPath.cpp builds them).
MotionQuery lineQuery(const Workspace& ws, const Pose3& target, const CollisionOptions& collision,
                      const std::vector<double>& lineOptions);

// FNV-1a over the bytes of `values`, finished with SplitMix64 (well mixed in every bit).
std::uint64_t fingerprintOf(const std::vector<double>& values);

// The answer to an arm or base query (one of the two paths is used).
struct MotionAnswer {
  PlanStatus status = PlanStatus::BudgetExhausted;
  int budget = 0;              // the RRTConnect budget it was computed with
  int iterations = 0;          // the iterations it used
  std::vector<ArmConfig> arm;  // MotionKind::Arm and Line
  std::vector<Pose2> base;     // MotionKind::Base
  bool solved() const { return status == PlanStatus::Solved; }
  // Whether this answer is the one a plan with `budget` iterations would give.
  bool answers(int wantedBudget) const {
    if (solved()) return iterations <= wantedBudget;
    if (status == PlanStatus::BudgetExhausted) return budget >= wantedBudget;
    return true;  // invalid start or goal: no budget changes that
  }
};

struct MotionCacheStats {
  std::uint64_t hits = 0, misses = 0, stored = 0, evicted = 0;
};

class MotionCache {
 public:
  explicit MotionCache(std::size_t capacity = 20000) : capacity_(capacity) {}

  // The cached answer to `q` that a plan with `budget` iterations would give, if any.
  std::optional<MotionAnswer> find(const MotionQuery& q, int budget);
  void store(const MotionQuery& q, MotionAnswer answer);
  MotionCacheStats stats() const;
  void clear();

 private:
  struct Entry {
    MotionKind kind;
    std::vector<double> key;
    MotionAnswer answer;
  };
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::unordered_map<std::uint64_t, Entry> entries_;
  std::deque<std::uint64_t> order_;  // fingerprints in insertion order (eviction)
  MotionCacheStats stats_;
};

// planArm / planBase (MotionPlanner.h) from the Workspace's current state, with the random stream seeded from
// the query's fingerprint, answered from the scene's cache when it holds the answer (the cached path, status and
// iterations; validity-check counts are not kept). The Workspace is left as planArm / planBase leave it.
ArmPlan planArmCached(Workspace& ws, const ArmConfig& goal, const PlanOptions& options);
BasePlan planBaseCached(Workspace& ws, const Pose2& goal, const PlanOptions& options);

}  // namespace cbtl::world
