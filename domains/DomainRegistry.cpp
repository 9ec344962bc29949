#include "domains/DomainRegistry.h"

#if defined(CBTL_HAVE_DOMAIN_BOOKS)
#include "domains/books/BooksSimulator.h"
#endif
#if defined(CBTL_HAVE_DOMAIN_CLEANING)
#include "domains/cleaning/CleaningSimulator.h"
#endif
#if defined(CBTL_HAVE_DOMAIN_COOKING)
#include "domains/cooking/CookingSimulator.h"
#endif
#if defined(CBTL_HAVE_DOMAIN_FEEDING)
#include "domains/feeding/FeedingActions.h"
#include "domains/feeding/FeedingSimulator.h"
#endif

#include <algorithm>

namespace cbtl::domains {

namespace {

using Factory = std::unique_ptr<sim::DomainSimulator> (*)(const ProgramFacts&, const sim::SimulatorOptions&,
                                                          std::uint64_t);

struct Entry {
  const char* name;
  Factory make;
};

// One line per built domain; a new domain adds its #if block here. The `robot` folder is the shared executor
// library, not a domain: it has no entry.
const std::vector<Entry>& entries() {
  static const std::vector<Entry> all = [] {
    std::vector<Entry> e;
#if defined(CBTL_HAVE_DOMAIN_BOOKS)
    e.push_back({"books",
                 [](const ProgramFacts& p, const sim::SimulatorOptions& o,
                    std::uint64_t seed) -> std::unique_ptr<sim::DomainSimulator> {
                   return std::make_unique<books::BooksSimulator>(p, o, seed);
                 }});
#endif
#if defined(CBTL_HAVE_DOMAIN_CLEANING)
    e.push_back({"cleaning",
                 [](const ProgramFacts& p, const sim::SimulatorOptions& o,
                    std::uint64_t seed) -> std::unique_ptr<sim::DomainSimulator> {
                   return std::make_unique<cleaning::CleaningSimulator>(p, o, seed);
                 }});
#endif
#if defined(CBTL_HAVE_DOMAIN_COOKING)
    e.push_back({"cooking",
                 [](const ProgramFacts&, const sim::SimulatorOptions& o,
                    std::uint64_t seed) -> std::unique_ptr<sim::DomainSimulator> {  // no scene, no items it reads
                   return std::make_unique<cooking::CookingSimulator>(o, seed);
                 }});
#endif
#if defined(CBTL_HAVE_DOMAIN_FEEDING)
    e.push_back({"feeding",
                 [](const ProgramFacts& p, const sim::SimulatorOptions& o,
                    std::uint64_t seed) -> std::unique_ptr<sim::DomainSimulator> {
                   return std::make_unique<feeding::FeedingSimulator>(p, o, seed);
                 }});
#endif
    std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) { return std::string(a.name) < b.name; });
    return e;
  }();
  return all;
}

}  // namespace

std::unique_ptr<sim::DomainSimulator> createSimulator(const std::string& domain, const ProgramFacts& program,
                                                      const sim::SimulatorOptions& options, std::uint64_t seed) {
  for (const Entry& e : entries()) {
    if (domain == e.name) return e.make(program, options, seed);
  }
  return nullptr;
}

std::shared_ptr<const actions::DomainActions> domainActions(const std::string& domain, const world::Scene& scene) {
#if defined(CBTL_HAVE_DOMAIN_FEEDING)
  if (domain == "feeding") return feeding::FeedingActions::forScene(scene);
#endif
  (void)domain;
  (void)scene;
  return nullptr;
}

SolverBudgets solverBudgets(const std::string& domain) {
  if (domain == "books" || domain == "cleaning" || domain == "feeding") return SolverBudgets{2500, 500, 100};
  return SolverBudgets{};
}

std::vector<std::string> knownDomains() {
  std::vector<std::string> names;
  for (const Entry& e : entries()) names.emplace_back(e.name);
  return names;
}

}  // namespace cbtl::domains
