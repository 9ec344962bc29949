// `cbtl simulator check FILE [--simulator CMD]`: starts the program's external simulator, checks its manifest
// against the program (every mismatch listed), resets and observes one world, then exercises it as a run would
// (app/SimulatorCheck.h: plans the solver produced acted call by call, idle, an evaluation twin) and says what it
// found, or the first request whose answer broke the protocol.
// `cbtl simulator serve FILE`: serves the program's in-process domain over the external simulator protocol on
// stdin/stdout (app/SimulatorServer.h). Exit codes: 0 ok, 1 bad input (a simulator that does not fit), 2 usage.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "app/SimulatorCheck.h"
#include "app/SimulatorServer.h"
#include "app/SimulatorSource.h"
#include "runtime/sim/ProtocolSchema.h"
#include "runtime/sim/SimulatorProtocol.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>
#include <string>

namespace {

struct SimulatorArgs {
  std::string file, stdlibDir;
  std::uint64_t seed = 0;
  cbtl::cli::ExternalSimulatorArgs external;
};

std::string plural(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

int runCheck(const SimulatorArgs& a) {
  using namespace cbtl;
  auto lp = cli::loadForRun("simulator check", a.file, a.stdlibDir);
  if (!lp) return 1;
  const auto external = app::externalSimulator(*lp, a.external.command, a.external.timeoutMs);
  if (!external) {
    fmt::print(stderr,
               "cbtl simulator check: error: {}: the program has no `simulator \"CMD\";` line and no --simulator was "
               "given\n",
               a.file);
    return 1;
  }
  std::vector<std::string> keys;
  for (const auto& [key, _] : lp->program().observationSlots()) keys.push_back(key);
  auto schema = std::make_shared<const sim::ProtocolSchema>(sim::ProtocolSchema::fromProgram(lp->graph(), keys));
  sim::ExternalSimulator world(*external, schema, {}, a.seed);
  for (const auto& w : world.manifestWarnings()) fmt::print("warning: {}\n", w);
  const sim::Observation observation = world.observe();
  fmt::print("simulator '{}' fits {}: protocol {}; {}, {}, {}, {}\n", world.simulatorName(), a.file,
             sim::protocol::kVersion, plural(schema->observationNames.size(), "observation", "observations"),
             plural(schema->actions.size(), "action", "actions"),
             plural(schema->feedback.size(), "feedback event", "feedback events"),
             plural(schema->tasks.size(), "task", "tasks"));
  fmt::print("observed at seed {}: {}\n", a.seed, sim::encodeObservation(*schema, observation).dump());
  if (!world.requestedTask().empty()) fmt::print("the world asks for task '{}'\n", world.requestedTask());

  // What a run does next (app/SimulatorCheck.h): plans acted, idle, a twin.
  std::vector<std::string> actions;
  for (const auto& [name, _] : schema->actions) actions.push_back(name);
  const app::SimulatorCheckReport report =
      app::exerciseSimulator(*lp, world, actions, a.seed, cli::solverOptionsFor(cli::SolverArgs{}, lp->graph().domain));
  fmt::print("exercised as a run would ({} plans solved, {} not):\n", report.plansSolved, report.plansUnsolved);
  for (const std::string& line : report.log) fmt::print("  {}\n", line);
  if (!report.ok()) {
    fmt::print(stderr, "cbtl simulator check: error: the simulator broke the protocol at {}\n", report.violation);
    return 1;
  }
  for (const std::string& name : report.notExercised)
    fmt::print("note: no plan called action '{}', so it was not exercised\n", name);
  if (!report.sawDone) fmt::print("note: no step answered `done`: a task that never ends never gets a new request\n");
  fmt::print("simulator '{}' answered every request: reset, observe, act, idle, twin\n", world.simulatorName());
  return 0;
}

int runServe(const SimulatorArgs& a) {
  using namespace cbtl;
  auto lp = cli::loadForRun("simulator serve", a.file, a.stdlibDir);
  if (!lp) return 1;
  std::ios::sync_with_stdio(false);
  return app::serveSimulator(*lp, std::cin, std::cout);
}

void addSimulator(CLI::App& app, int& exitCode) {
  CLI::App* group = app.add_subcommand(
      "simulator", "external simulators: check one against a program, or serve a built-in domain over the protocol");
  group->require_subcommand(1);

  auto check = std::make_shared<SimulatorArgs>();
  CLI::App* c = group->add_subcommand(
      "check", "start the program's simulator, check its manifest, then exercise it as a run would (act, idle, twin)");
  c->add_option("file", check->file, "the domain's .cbtl file")->required();
  c->add_option("--seed", check->seed, "the seed of the world observed")->capture_default_str();
  c->add_option("--stdlib", check->stdlibDir, "standard library folder (default: embedded)");
  cbtl::cli::addExternalSimulatorOptions(c, check->external);
  c->callback(
      [check, &exitCode] { cbtl::cli::runCommand("simulator check", exitCode, [&] { return runCheck(*check); }); });

  auto serve = std::make_shared<SimulatorArgs>();
  CLI::App* s = group->add_subcommand(
      "serve", "serve the program's built-in domain simulator over the external simulator protocol on stdin/stdout");
  s->add_option("file", serve->file, "the domain's .cbtl file")->required();
  s->add_option("--stdlib", serve->stdlibDir, "standard library folder (default: embedded)");
  s->callback(
      [serve, &exitCode] { cbtl::cli::runCommand("simulator serve", exitCode, [&] { return runServe(*serve); }); });
}

const cbtl::cli::RegisterCommand registerSimulator(45, addSimulator);

}  // namespace
