// Cleaning joins the domain registry (domains/DomainRegistry.h), with the robot domains' budgets.
#include "domains/DomainRegistry.h"
#include "domains/cleaning/CleaningSimulator.h"

namespace cbtl::domains {

void registerDomain_cleaning(DomainCatalog& catalog) {
  catalog.add({"cleaning",
               [](const ProgramFacts& p, const sim::SimulatorOptions& o, std::uint64_t seed) {
                 return std::unique_ptr<sim::DomainSimulator>(
                     std::make_unique<cleaning::CleaningSimulator>(p, o, seed));
               },
               {},
               SolverBudgets{2500, 500, 100}});
}

}  // namespace cbtl::domains
