#include "runtime/approach/Planner.h"

namespace cbtl::approach {

namespace {

solver::Csp makeTaskCsp(const PreparedProgram& lp, std::size_t task, const std::vector<double>& observation,
                        solver::PersonalMode personal, solver::CostKind cost, const model::UserModel& user,
                        PlanExecution* execution) {
  solver::Csp csp = solver::makeCsp(lp.program(), static_cast<std::uint32_t>(task), lp.instances(task), user,
                                    observation, personal, cost);
  if (execution != nullptr) attachPlan(csp, *execution, lp.actions(task));
  return csp;
}

bool interrupted(const Plan& plan) { return plan.solve.outcome == solver::SolveOutcome::Interrupted; }

// Solves plan.csp, tier after dry-run tier (cheapest first) until one finds a solution or a person interrupts (the
// tiers after an interruption never run, so they are not reported as failed).
void solveTiered(const PreparedProgram& lp, Plan& plan, solver::Solver& solver) {
  const std::vector<int>& tiers = lp.dryRunTiers();
  std::size_t tier = 0;
  do {
    if (tier > 0) plan.failedTiers.emplace_back(plan.motionIterations, std::move(plan.solve));
    if (plan.execution) {
      plan.motionIterations = tiers.empty() ? 0 : tiers[tier];
      plan.execution->setMotionIterations(plan.motionIterations);
    }
    plan.solve = solver.solve(plan.csp);
    plan.iterations += plan.solve.iterations;
    ++plan.tiersRun;
  } while (!plan.solve.solved() && !interrupted(plan) && plan.execution && ++tier < tiers.size());
}

}  // namespace

Plan makePlan(const PreparedProgram& lp, std::size_t task, const std::vector<double>& observation, CspChoice choice,
              bool fallback, solver::Solver& solver, const model::UserModel& user) {
  Plan plan;
  plan.execution = makePlanExecution(lp, task);
  plan.csp = makeTaskCsp(lp, task, observation, choice.personal, choice.cost, user, plan.execution.get());
  solveTiered(lp, plan, solver);
  if (!plan.solve.solved() && !interrupted(plan) && fallback && choice.personal == solver::PersonalMode::Include) {
    plan.failedFull = std::move(plan.solve);
    plan.csp = makeTaskCsp(lp, task, observation, solver::PersonalMode::Exclude,
                           choice.cost == solver::CostKind::Entropy ? solver::CostKind::None : choice.cost, user,
                           plan.execution.get());
    solveTiered(lp, plan, solver);
    plan.replanned = true;
  }
  plan.ok = plan.solve.solved();
  if (plan.ok) {
    plan.rechecked = true;
    plan.recheck = solver::recheck(plan.csp, plan.solve.assignment);
    plan.ok = plan.recheck.holds();
  }
  if (!plan.ok) return plan;
  if (plan.execution) {
    const OwnedContext at(lp.program(), plan.solve.assignment, plan.csp.observation);
    plan.calls = plan.execution->calls(at.ctx);
  } else {
    plan.calls = lp.actions(task).unroll(lp.program(), plan.solve.assignment, observation);
  }
  return plan;
}

}  // namespace cbtl::approach
