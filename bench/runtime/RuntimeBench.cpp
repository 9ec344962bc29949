// Runtime benchmarks (docs/runtime.md has the figures and the command):
//   BM_CookingTrial/<approach>: one full trial of the paper's protocol — 10,000 training steps and 101
//     evaluations of 10 held-out tasks — target under 1 s on one core (the reference: 75-121 s).
//   BM_SolverThroughput/<csp>: candidates per second of the sampling solver on Cooking CSPs: exploit (hard and
//     personalized constraints, first feasible), explore (hard constraints, maximize entropy, learned models).
#include "app/LoadedProgram.h"
#include "bench/runtime/BenchPrograms.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Solver.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

namespace {

using namespace cbtl;

const app::LoadedProgram& cooking() { return bench::domainProgram("cooking"); }

approach::SimulatorFactory factory() {
  return [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator("cooking", {}, o, seed);
  };
}

void BM_CookingTrial(benchmark::State& state) {
  const auto& lp = cooking();
  approach::ExperimentConfig c;
  c.approach.kind = static_cast<approach::ApproachKind>(state.range(0));
  std::uint64_t seed = 0;
  std::uint64_t iterations = 0;
  for (auto _ : state) {
    c.seed = seed++ % 10;
    const auto r = approach::runExperiment(lp, factory(), c);
    iterations += r.solverIterations;
    benchmark::DoNotOptimize(r.meanEval());
  }
  state.SetLabel(approach::toString(c.approach.kind));
  state.counters["train_solver_iters"] =
      benchmark::Counter(static_cast<double>(iterations) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_CookingTrial)
    ->Arg(static_cast<int>(approach::ApproachKind::Cbtl))
    ->Arg(static_cast<int>(approach::ApproachKind::NoPersonalization))
    ->Arg(static_cast<int>(approach::ApproachKind::ExploitOnly))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// A user model learned by CBTL for 2,000 steps, so the entropy landscape is the interesting one.
const model::UserModel& learnedUser() {
  static const auto user = [] {
    const auto& lp = cooking();
    approach::ExperimentConfig c;
    c.steps = 2000;
    c.evalEvery = 2000;
    c.evalTasks = 1;
    c.outDir = "";
    auto dir = std::filesystem::temp_directory_path() / "cbtl_bench_profile";
    c.outDir = dir.string();
    approach::runExperiment(lp, factory(), c);
    auto u = std::make_unique<model::UserModel>(lp.graph());
    u->load((dir / "profile.json").string());
    return u;
  }();
  return *user;
}

void BM_SolverThroughput(benchmark::State& state) {
  const auto& lp = cooking();
  const auto& user = learnedUser();
  auto world = domains::createSimulator("cooking", {}, {}, 1);
  const auto obs = approach::observationVector(lp.program(), world->observe());
  const bool explore = state.range(0) == 1;
  const auto csp = solver::makeCsp(lp.program(), 0, lp.instances(0), user, obs,
                                   explore ? solver::PersonalMode::Exclude : solver::PersonalMode::Include,
                                   explore ? solver::CostKind::Entropy : solver::CostKind::None);
  solver::Solver solver({}, 5);
  std::uint64_t candidates = 0, iterations = 0;
  for (auto _ : state) {
    const auto r = solver.solve(csp);
    candidates += r.candidatesChecked;
    iterations += r.iterations;
    benchmark::DoNotOptimize(r.assignment.data());
  }
  state.SetLabel(explore ? "explore" : "exploit");
  state.counters["iterations/s"] = benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kIsRate);
  state.counters["candidates/s"] = benchmark::Counter(static_cast<double>(candidates), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SolverThroughput)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
