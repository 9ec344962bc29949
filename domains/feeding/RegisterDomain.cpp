// Feeding joins the domain registry (domains/DomainRegistry.h): its simulator, its own actions on the robot world
// (the utensil and the drink, FeedingActions.h) for the runtime's world model, and the robot domains' budgets.
#include "domains/DomainRegistry.h"
#include "domains/feeding/FeedingActions.h"
#include "domains/feeding/FeedingSimulator.h"

namespace cbtl::domains {

void registerDomain_feeding(DomainCatalog& catalog) {
  catalog.add({"feeding",
               [](const ProgramFacts& p, const sim::SimulatorOptions& o, std::uint64_t seed) {
                 return std::unique_ptr<sim::DomainSimulator>(std::make_unique<feeding::FeedingSimulator>(p, o, seed));
               },
               [](const world::Scene& scene) { return feeding::FeedingActions::forScene(scene); },
               SolverBudgets{2500, 500, 100}});
}

}  // namespace cbtl::domains
