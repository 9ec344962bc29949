// StagedPlan.h — what the solver needs to accept only candidates whose plan the world can carry out.
//
// A task's skills run one after another; skill k is the plan's *stage* k. Constraints and samplers of stage k
// are evaluated in the world state stages 0..k-1 leave (an object placed, the gripper empty, the base moved),
// and after every other constraint holds, the whole plan is dry-run in the world with every check the executor
// applies: the implicit constraint PlanExecutes (Csp.h), always checked last, charged with the rejection when
// some action would fail.
//
// A candidate for which a stage has no defined start state (an earlier action's effect is undefined, e.g. no IK
// for a tool move) is rejected by that stage's first constraint, and the rejection is charged to PlanExecutes
// with the failing action (SolveResult::planFailures), since that is what it is.
// The solver calls enterStage before evaluating anything of a stage; the state a stage starts in depends on
// the values the earlier stages' actions read (readsBefore), so those variables count as read by every
// constraint, sampler and personalized instance of the stage: a move that changes one re-evaluates them.
// The implementation (runtime/approach/PlanExecution.h) unrolls the actions for the current candidate and asks
// the world model (runtime/sim/ExecutionModel.h).
#pragma once

#include "ir/ConstraintGraph.h"
#include "runtime/core/Expression.h"
#include "runtime/sim/ExecutionModel.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbtl::solver {

inline constexpr const char* kPlanExecutesName = "planExecutes";
// The stage of a constraint, sampler or instance that reads nothing of the world: it is evaluated in whatever
// state the world shows (no stage is entered for it, and no earlier action's variables re-evaluate it).
inline constexpr std::uint32_t kAnyStage = UINT32_MAX;

class StagedPlan {
 public:
  virtual ~StagedPlan() = default;

  virtual std::size_t stageCount() const = 0;
  // Variables the actions of stages 0..stage-1 read (empty for stage 0).
  virtual const std::vector<ir::VarId>& readsBefore(std::size_t stage) const = 0;
  // Variables any action of the plan reads: the PlanExecutes constraint's variables.
  virtual const std::vector<ir::VarId>& reads() const = 0;

  // The assignment in `ctx` changed in a variable of reads(): forget the unrolled plan.
  virtual void changed() = 0;
  // Makes the world built-ins read the state `stage` starts in for the assignment in `ctx`. false when an
  // earlier stage's effect is undefined for it (the built-ins then read the observed state).
  virtual bool enterStage(std::size_t stage, const rt::EvalContext& ctx) = 0;
  // For samplers, which only propose values: makes the built-ins read the state `stage` started in for the
  // latest candidate whose earlier stages were unrolled (exactly enterStage when the current one was; the
  // observed state when none was yet). Never unrolls, so drawing a later skill's values costs no effects.
  virtual void enterRecentStage(std::size_t stage) = 0;
  // Dry-runs the whole plan for the assignment in `ctx`.
  virtual sim::PlanVerdict check(const rt::EvalContext& ctx) = 0;
  // After enterStage returned false: the earlier action whose effect is undefined, and why.
  virtual sim::PlanVerdict stageFailure() const = 0;
};

}  // namespace cbtl::solver
