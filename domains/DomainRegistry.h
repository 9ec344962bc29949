// DomainRegistry.h — the in-process domains: each creates its simulator by the domain's name (the `domain` line
// of its .cbtl file), from the facts of the loaded program (ProgramFacts.h: its scene and item sets).
//
// Domains register themselves: a folder domains/<name>/ that has a CMakeLists.txt (defining cbtl_domain_<name>)
// and a RegisterDomain.cpp (defining `void registerDomain_<name>(DomainCatalog&)`) joins the build and this
// registry, with no edit of a central file (domains/CMakeLists.txt generates the list of calls). A domain that
// needs no C++ at all names an external simulator instead (docs/simulator-protocol.md).
//
// The registry owns nothing: each call makes a new, independent simulator.
#pragma once

#include "domains/ProgramFacts.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::actions {
class DomainActions;
}
namespace cbtl::world {
class Scene;
}

namespace cbtl::domains {

// A domain's solver budgets, used where the command line gives none: the reference's per-environment settings
// (Cooking: 100,000 iterations, 500 improvements, 10,000 attempts after the first solution; the robot domains:
// 2,500 / 500 / 100, since every candidate that reaches the plan check is dry-run in the world).
struct SolverBudgets {
  std::uint64_t maxIters = 100000;
  std::uint64_t numImprovements = 500;
  std::uint64_t maxImprovementAttempts = 10000;
};

// What a domain registers.
struct DomainEntry {
  std::string name;  // the `domain` name of its programs
  // A new simulator over the program's facts, constructed with the options and reset with the seed; throws what
  // the domain's constructor throws for invalid options or facts.
  std::function<std::unique_ptr<sim::DomainSimulator>(const ProgramFacts&, const sim::SimulatorOptions&, std::uint64_t)>
      makeSimulator;
  // The domain's own actions on the robot world, the same ones its simulator executes; empty: none.
  std::function<std::shared_ptr<const actions::DomainActions>(const world::Scene&)> makeActions;
  SolverBudgets budgets;
};

class DomainCatalog {
 public:
  // Adds a domain; a second domain of the same name is a build mistake (std::logic_error).
  void add(DomainEntry entry);
  const DomainEntry* find(const std::string& name) const;
  const std::vector<DomainEntry>& entries() const { return entries_; }

 private:
  std::vector<DomainEntry> entries_;  // sorted by name
};

// Every domain that was built, registered once.
const DomainCatalog& builtDomains();

// A new simulator for `domain` (e.g. "cooking") over the program's facts, constructed with `options` and reset
// with `seed`; nullptr when no simulator of that name was built. Throws what the domain's constructor throws for
// invalid options or facts (a robot domain without a scene: std::invalid_argument).
std::unique_ptr<sim::DomainSimulator> createSimulator(const std::string& domain, const ProgramFacts& program,
                                                      const sim::SimulatorOptions& options, std::uint64_t seed);

// The domain's own actions on the robot world (robot/actions/RobotActions.h DomainActions) for the runtime's
// world model, the same ones its simulator executes; null when the domain has none (or none was built).
std::shared_ptr<const actions::DomainActions> domainActions(const std::string& domain, const world::Scene& scene);

// The budgets `domain` registered; the defaults above for a domain that was not built (an external one).
SolverBudgets solverBudgets(const std::string& domain);

// The names createSimulator accepts, sorted.
std::vector<std::string> knownDomains();

}  // namespace cbtl::domains
