#include "app/SimulatorSource.h"

#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "domains/ProgramFacts.h"

#include <filesystem>

namespace cbtl::app {

namespace fs = std::filesystem;

namespace {

std::shared_ptr<const sim::ProtocolSchema> schemaOf(const LoadedProgram& program) {
  std::vector<std::string> keys;
  for (const auto& [key, _] : program.program().observationSlots()) keys.push_back(key);
  return std::make_shared<const sim::ProtocolSchema>(sim::ProtocolSchema::fromProgram(program.graph(), keys));
}

}  // namespace

std::optional<sim::ExternalSimulatorConfig> externalSimulator(const LoadedProgram& program,
                                                              const std::string& commandLine, int timeoutMs) {
  sim::ExternalSimulatorConfig c;
  c.timeoutMs = timeoutMs;
  if (!commandLine.empty()) {
    c.command = commandLine;
    return c;
  }
  const ir::ConstraintGraph& g = program.graph();
  if (g.simulator.empty()) return std::nullopt;
  c.command = g.simulator;
  c.origin = domains::whereOf(g.simulatorSpan);
  const fs::path folder = fs::path(program.path()).parent_path();
  c.workingDirectory = folder.empty() ? "." : folder.string();
  return c;
}

namespace {

// A robot program's CSP is checked against the robot world the runtime keeps in step with the simulator's scene
// (plans are dry-run in it before they are accepted). That state does not cross the protocol, so an external
// simulator would leave every check reading a world that never moves: refused, whatever the simulator says.
void refuseRobotScene(const LoadedProgram& program, const sim::ExternalSimulatorConfig& external) {
  if (program.graph().world.empty()) return;
  throw sim::ExternalSimulatorError(
      external.origin,
      "the program has a robot scene (world \"" + program.graph().world +
          "\"): its state is what every plan is checked against before it is accepted, and it does not cross the "
          "external simulator protocol; a robot domain runs with its built-in simulator");
}

}  // namespace

std::unique_ptr<sim::DomainSimulator> createSimulator(const LoadedProgram& program,
                                                      const std::optional<sim::ExternalSimulatorConfig>& external,
                                                      const sim::SimulatorOptions& options, std::uint64_t seed) {
  return simulatorFactory(program, external)(options, seed);
}

approach::SimulatorFactory simulatorFactory(const LoadedProgram& program,
                                            const std::optional<sim::ExternalSimulatorConfig>& external) {
  if (external) {
    refuseRobotScene(program, *external);
    auto schema = schemaOf(program);
    return [config = *external, schema](const sim::SimulatorOptions& options,
                                        std::uint64_t seed) -> std::unique_ptr<sim::DomainSimulator> {
      return std::make_unique<sim::ExternalSimulator>(config, schema, options, seed);
    };
  }
  auto facts = std::make_shared<const domains::ProgramFacts>(simulatorFacts(program));
  return [domain = program.graph().domain, facts](const sim::SimulatorOptions& options, std::uint64_t seed) {
    return domains::createSimulator(domain, *facts, options, seed);
  };
}

}  // namespace cbtl::app
