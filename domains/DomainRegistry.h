// DomainRegistry.h — creates a domain's simulator by the domain's name (the `domain` line of its .cbtl file),
// from the facts of the loaded program (ProgramFacts.h: its scene and item sets).
//
// Only the domains whose library was built are known; the build links every domains/<name>/ folder that has a
// CMakeLists.txt. The registry owns nothing: each call makes a new, independent simulator.
#pragma once

#include "domains/ProgramFacts.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstdint>
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

// A new simulator for `domain` (e.g. "cooking") over the program's facts, constructed with `options` and reset
// with `seed`; nullptr when no simulator of that name was built. Throws what the domain's constructor throws for
// invalid options or facts (a robot domain without a scene: std::invalid_argument).
std::unique_ptr<sim::DomainSimulator> createSimulator(const std::string& domain, const ProgramFacts& program,
                                                      const sim::SimulatorOptions& options, std::uint64_t seed);

// The domain's own actions on the robot world (robot/actions/RobotActions.h DomainActions) for the runtime's
// world model, the same ones its simulator executes; null when the domain has none (or none was built).
std::shared_ptr<const actions::DomainActions> domainActions(const std::string& domain, const world::Scene& scene);

// A domain's solver budgets, used where the command line gives none: the reference's per-environment settings
// (Cooking: 100,000 iterations, 500 improvements, 10,000 attempts after the first solution; the robot domains:
// 2,500 / 500 / 100, since every candidate that reaches the plan check is dry-run in the world).
struct SolverBudgets {
  std::uint64_t maxIters = 100000;
  std::uint64_t numImprovements = 500;
  std::uint64_t maxImprovementAttempts = 10000;
};
SolverBudgets solverBudgets(const std::string& domain);

// The names createSimulator accepts, sorted.
std::vector<std::string> knownDomains();

}  // namespace cbtl::domains
