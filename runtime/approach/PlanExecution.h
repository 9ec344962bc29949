// PlanExecution.h — a task's plan checked in the world while the solver searches (solver/StagedPlan.h): the
// task's skills as stages, each unrolled in the state the earlier ones leave, and the whole plan dry-run by the
// program's world model (runtime/sim/ExecutionModel.h).
//
// Which tasks are checked: every task of a program whose built-ins' host has an execution model (a robot
// domain's world) and whose actions that model all knows. A .cbtl author writes nothing for it: a plan the
// world cannot carry out is never a solution, and `cbtl solve --explain` charges such candidates to the
// implicit constraint `planExecutes` with the failing action and reason (docs/language.md, "Plans that
// execute").
//
// The unrolled plan is kept until the solver reports a change of a variable the actions read (changed()); the
// world model caches stage states and verdicts by fingerprint, so re-entering a stage is cheap.
#pragma once

#include "runtime/approach/ActionPlan.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/StagedPlan.h"

#include <memory>
#include <optional>
#include <vector>

namespace cbtl::approach {

class PreparedProgram;

class PlanExecution final : public solver::StagedPlan {
 public:
  PlanExecution(const rt::Program& program, const TaskActions& actions, sim::ExecutionModel& model);

  std::size_t stageCount() const override { return actions_.stageCount(); }
  const std::vector<ir::VarId>& readsBefore(std::size_t stage) const override { return actions_.readsBefore(stage); }
  const std::vector<ir::VarId>& reads() const override { return actions_.reads(); }
  void changed() override { unrolled_ = false; }
  bool enterStage(std::size_t stage, const rt::EvalContext& ctx) override;
  void enterRecentStage(std::size_t stage) override;
  sim::PlanVerdict check(const rt::EvalContext& ctx) override;
  sim::PlanVerdict stageFailure() const override { return effectFailure_.value_or(sim::PlanVerdict{}); }

  // The calls of the whole plan for the assignment in `ctx`, each stage unrolled in the state the earlier
  // stages leave (the built-ins read the observed state afterwards).
  std::vector<sim::ActionCall> calls(const rt::EvalContext& ctx);

  // Planner iterations each motion of the dry run may take (0: straight segments only).
  void setMotionIterations(int iterations) { motionIterations_ = iterations; }
  int motionIterations() const { return motionIterations_; }

 private:
  void unroll(const rt::EvalContext& ctx);

  const rt::Program& program_;
  const TaskActions& actions_;
  sim::ExecutionModel& model_;
  int motionIterations_ = 0;
  bool unrolled_ = false;
  std::vector<sim::ActionCall> calls_;
  std::vector<std::size_t> stageStart_;                     // first call of each stage
  std::size_t definedStages_ = 0;                           // stages whose start state is defined
  std::optional<sim::PlanVerdict> effectFailure_;           // why stage definedStages_ has none
  std::vector<std::vector<sim::ActionCall>> recentPrefix_;  // per stage: the last defined prefix
};

// A PlanExecution for task `task` when the program's world has an execution model that knows every action the
// task calls; null otherwise (then nothing is staged or dry-run).
std::unique_ptr<PlanExecution> makePlanExecution(const PreparedProgram& lp, std::size_t task);

// Attaches `plan` to `csp`: the stage of every constraint, sampler and personalized instance, the constraints
// reordered stage by stage (stably: personalized first within a stage), and the implicit PlanExecutes
// constraint, checked last.
void attachPlan(solver::Csp& csp, PlanExecution& plan, const TaskActions& actions);

// An evaluation context over copies of `assignment` and `observation` padded to the program's widths.
struct OwnedContext {
  OwnedContext(const rt::Program& program, const std::vector<double>& assignment,
               const std::vector<double>& observation);
  OwnedContext(const OwnedContext&) = delete;  // ctx points into the vectors
  OwnedContext& operator=(const OwnedContext&) = delete;
  std::vector<double> x, obs, frame;
  rt::EvalContext ctx;
};

}  // namespace cbtl::approach
