// What the external simulator protocol costs (docs/simulator-protocol.md; figures and commands: docs/results.md):
//   BM_CookingCalls/<0 in process | 1 over the protocol>: one Cooking episode's simulator calls (reset, observe,
//     the plan's act calls) against the built-in Cooking simulator, directly and through `cbtl simulator serve`;
//     `calls` is the number of calls one iteration makes and `per_call` the wall-clock time of one.
//   BM_CookingTrialOverProtocol/<0 | 1>: a whole Cooking trial (CBTL, 2,000 steps, 21 evaluations of 10 tasks) in
//     process and over the protocol: the ratio is what a Cooking-sized external domain pays (target: within 3x).
#include "app/LoadedProgram.h"
#include "app/SimulatorSource.h"
#include "bench/runtime/BenchPrograms.h"
#include "runtime/approach/Experiment.h"
#include "runtime/sim/ExternalSimulator.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

namespace {

using namespace cbtl;

const app::LoadedProgram& cookingProgram() { return bench::domainProgram("cooking"); }

std::optional<sim::ExternalSimulatorConfig> served(bool overProtocol) {
  if (!overProtocol) return std::nullopt;
  sim::ExternalSimulatorConfig c;
  c.command = std::string(CBTL_BIN) + " simulator serve " + CBTL_DOMAINS_DIR + "/cooking/cooking.cbtl";
  return c;
}

// One meal's calls: two pots, salt and pepper added, 30 ticks, serve.
std::vector<sim::ActionCall> mealCalls() {
  using sim::Value;
  std::vector<sim::ActionCall> calls;
  calls.push_back({"movePot", {Value::name("pot0"), Value::vec({2, 2})}});
  calls.push_back({"movePot", {Value::name("pot1"), Value::vec({6, 6})}});
  calls.push_back({"addIngredient", {Value::name("salt"), Value::name("pot0"), Value::num(1.0)}});
  calls.push_back({"addIngredient", {Value::name("pepper"), Value::name("pot1"), Value::num(1.0)}});
  for (int t = 0; t < 30; ++t) calls.push_back({"endTick", {}});
  calls.push_back({"serve", {Value::name("seasoning")}});
  return calls;
}

void BM_CookingCalls(benchmark::State& state) {
  const auto& lp = cookingProgram();
  auto world = app::createSimulator(lp, served(state.range(0) != 0), {}, 0);
  const auto calls = mealCalls();
  std::uint64_t seed = 0;
  for (auto _ : state) {
    world->reset(seed++);
    benchmark::DoNotOptimize(world->observe());
    for (const auto& call : calls) benchmark::DoNotOptimize(world->act(call));
  }
  state.SetLabel(state.range(0) != 0 ? "over the protocol" : "in process");
  state.counters["calls"] = static_cast<double>(calls.size() + 2);
  // Wall-clock seconds per call (the server's time is not this process's CPU time).
  state.counters["per_call"] =
      benchmark::Counter(static_cast<double>(calls.size() + 2),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CookingCalls)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_CookingTrialOverProtocol(benchmark::State& state) {
  const auto& lp = cookingProgram();
  const auto factory = app::simulatorFactory(lp, served(state.range(0) != 0));
  approach::ExperimentConfig c;
  c.steps = 2000;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    c.seed = seed++;
    benchmark::DoNotOptimize(approach::runExperiment(lp, factory, c).meanEval());
  }
  state.SetLabel(state.range(0) != 0 ? "over the protocol" : "in process");
}
BENCHMARK(BM_CookingTrialOverProtocol)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
