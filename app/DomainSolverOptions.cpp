#include "app/DomainSolverOptions.h"

#include "domains/DomainRegistry.h"

namespace cbtl::app {

solver::SolverOptions domainSolverOptions(const std::string& domain) {
  const domains::SolverBudgets b = domains::solverBudgets(domain);
  solver::SolverOptions o;
  o.maxIters = b.maxIters;
  o.numImprovements = b.numImprovements;
  o.maxImprovementAttempts = b.maxImprovementAttempts;
  return o;
}

}  // namespace cbtl::app
