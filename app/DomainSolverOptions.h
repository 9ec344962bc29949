// DomainSolverOptions.h — the solver options a program of a domain gets when nobody chose its budgets: the
// domain's declared iteration budgets (domains/DomainRegistry.h solverBudgets) on the solver's defaults.
#pragma once

#include "runtime/solver/Solver.h"

#include <string>

namespace cbtl::app {

solver::SolverOptions domainSolverOptions(const std::string& domain);

}  // namespace cbtl::app
