#include "runtime/approach/Planner.h"

namespace cbtl::approach {

Plan makePlan(const PreparedProgram& lp, std::size_t task, const std::vector<double>& observation, CspChoice choice,
              bool fallback, solver::Solver& solver, const model::UserModel& user) {
  Plan plan;
  plan.csp = solver::makeCsp(lp.program(), static_cast<std::uint32_t>(task), lp.instances(task), user, observation,
                             choice.personal, choice.cost);
  plan.solve = solver.solve(plan.csp);
  if (!plan.solve.solved() && fallback && choice.personal == solver::PersonalMode::Include) {
    plan.failedFull = std::move(plan.solve);
    plan.csp = solver::makeCsp(lp.program(), static_cast<std::uint32_t>(task), lp.instances(task), user, observation,
                               solver::PersonalMode::Exclude,
                               choice.cost == solver::CostKind::Entropy ? solver::CostKind::None : choice.cost);
    plan.solve = solver.solve(plan.csp);
    plan.replanned = true;
  }
  plan.ok = plan.solve.solved();
  if (plan.ok) {
    plan.rechecked = true;
    plan.recheck = solver::recheck(plan.csp, plan.solve.assignment);
    plan.ok = plan.recheck.holds();
  }
  if (plan.ok) plan.calls = lp.actions(task).unroll(lp.program(), plan.solve.assignment, observation);
  return plan;
}

}  // namespace cbtl::approach
