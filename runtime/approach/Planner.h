// Planner.h — one request: build the CSP the approach asks for, solve it, fall back if allowed, re-check the
// solution from scratch, and unroll it into action calls. Nothing reaches `calls` without passing the re-check.
// In a robot domain the task's plan is staged and dry-run while the solver searches (PlanExecution.h), so the
// calls are ones the world model carried out from the observed state.
#pragma once

#include "runtime/approach/Approach.h"
#include "runtime/approach/PlanExecution.h"
#include "runtime/approach/PreparedProgram.h"
#include "runtime/solver/Recheck.h"
#include "runtime/solver/Solver.h"

#include <optional>
#include <vector>

namespace cbtl::approach {

struct Plan {
  bool ok = false;
  // The staged, dry-run plan of a robot domain's task (null otherwise); csp.plan points to it.
  std::unique_ptr<PlanExecution> execution;
  bool dryRun() const { return execution != nullptr; }
  bool replanned = false;                         // the full CSP failed; solved without personal constraints
  solver::Csp csp;                                // the CSP that was solved last
  solver::SolveResult solve;                      // its result (the last dry-run tier's)
  std::optional<solver::SolveResult> failedFull;  // the failed full solve (its last tier's), when replanned
  // Dry-run tiers (PreparedProgram::dryRunTiers): the motion budget of the tier that solved (or was tried last),
  // how many tiers ran, and the solver iterations of every solve, tiers and replan included.
  int motionIterations = 0;
  int tiersRun = 0;
  std::uint64_t iterations = 0;
  // The solves of cheaper tiers that found no solution, in order, with their motion budgets (for --explain).
  std::vector<std::pair<int, solver::SolveResult>> failedTiers;
  std::vector<sim::ActionCall> calls;
  // The independent re-check of the solution (Recheck.h), run on every Solved result. A solution that fails it
  // is refused: `ok` is false and `calls` is empty.
  bool rechecked = false;
  solver::RecheckResult recheck;
  bool refused() const { return rechecked && !recheck.holds(); }
};

Plan makePlan(const PreparedProgram& lp, std::size_t task, const std::vector<double>& observation, CspChoice choice,
              bool fallback, solver::Solver& solver, const model::UserModel& user);

}  // namespace cbtl::approach
