// Books joins the domain registry (domains/DomainRegistry.h), with the robot domains' budgets.
#include "domains/DomainRegistry.h"
#include "domains/books/BooksSimulator.h"

namespace cbtl::domains {

void registerDomain_books(DomainCatalog& catalog) {
  catalog.add({"books",
               [](const ProgramFacts& p, const sim::SimulatorOptions& o, std::uint64_t seed) {
                 return std::unique_ptr<sim::DomainSimulator>(std::make_unique<books::BooksSimulator>(p, o, seed));
               },
               {},
               SolverBudgets{2500, 500, 100}});
}

}  // namespace cbtl::domains
