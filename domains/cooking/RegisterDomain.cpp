// Cooking joins the domain registry (domains/DomainRegistry.h): its simulator needs no scene and reads no item set;
// the reference's Cooking budgets (the registry's defaults).
#include "domains/DomainRegistry.h"
#include "domains/cooking/CookingSimulator.h"

namespace cbtl::domains {

void registerDomain_cooking(DomainCatalog& catalog) {
  catalog.add({"cooking",
               [](const ProgramFacts&, const sim::SimulatorOptions& o, std::uint64_t seed) {
                 return std::unique_ptr<sim::DomainSimulator>(std::make_unique<cooking::CookingSimulator>(o, seed));
               },
               {},
               SolverBudgets{}});
}

}  // namespace cbtl::domains
