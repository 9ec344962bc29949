// Planner.h — one request: build the CSP the approach asks for, solve it, fall back if allowed, and unroll
// the solution into action calls.
#pragma once

#include "Approach.h"
#include "LoadedProgram.h"
#include "Solver.h"

#include <optional>
#include <vector>

namespace cbtl::approach {

struct Plan {
  bool ok = false;
  bool replanned = false;                        // the full CSP failed; solved without personal constraints
  solver::Csp csp;                               // the CSP that was solved last
  solver::SolveResult solve;                     // its result
  std::optional<solver::SolveResult> failedFull; // the failed full solve, when replanned
  std::vector<sim::ActionCall> calls;
};

Plan makePlan(const LoadedProgram& lp, std::size_t task, const std::vector<double>& observation, CspChoice choice,
              bool fallback, solver::Solver& solver, const model::UserModel& user);

}  // namespace cbtl::approach
