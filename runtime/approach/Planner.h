// Planner.h — one request: build the CSP the approach asks for, solve it, fall back if allowed, re-check the
// solution from scratch, and unroll it into action calls. Nothing reaches `calls` without passing the re-check.
#pragma once

#include "runtime/approach/Approach.h"
#include "runtime/approach/PreparedProgram.h"
#include "runtime/solver/Recheck.h"
#include "runtime/solver/Solver.h"

#include <optional>
#include <vector>

namespace cbtl::approach {

struct Plan {
  bool ok = false;
  bool replanned = false;                         // the full CSP failed; solved without personal constraints
  solver::Csp csp;                                // the CSP that was solved last
  solver::SolveResult solve;                      // its result
  std::optional<solver::SolveResult> failedFull;  // the failed full solve, when replanned
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
