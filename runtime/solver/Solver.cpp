#include "runtime/solver/Solver.h"

#include "runtime/solver/SolveRun.h"

namespace cbtl::solver {

const char* toString(SolveOutcome o) {
  switch (o) {
    case SolveOutcome::Solved:
      return "Solved";
    case SolveOutcome::InfeasibleWithinBudget:
      return "InfeasibleWithinBudget";
    case SolveOutcome::SamplersStuck:
      return "SamplersStuck";
    case SolveOutcome::NoSamplers:
      return "NoSamplers";
    case SolveOutcome::Interrupted:
      return "Interrupted";
  }
  return "?";
}

std::size_t Solver::memoryEntries() const {
  std::size_t n = 0;
  for (const auto& [k, m] : memory_) n += m.size();
  return n;
}

SolveResult Solver::solve(const Csp& csp) { return SolveRun(options_, rng_, memory_, csp).run(); }

}  // namespace cbtl::solver
