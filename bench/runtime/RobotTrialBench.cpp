// Robot-domain benchmarks (docs/runtime.md, "Speed", has the figures and the command):
//   BM_RobotTrial/<domain>: one CBTL trial of the paper's protocol — 5,000 training steps, evaluation every 500
//     steps on 10 held-out tasks — with the domain's default budgets, every plan staged and dry-run. Target:
//     under 60 s on one core (the reference: 30-90 minutes per trial).
//   BM_RobotRequest/<domain>: one request (solve, dry run, re-check) against a fresh episode, cycling seeds 0-9;
//     the time a user waits for `cbtl solve`. Counter median_ms: the median request of the run. Target for
//     Feeding: under 20 ms.
//   BM_FeedingRun: one CBTL run as `cbtl run domains/feeding/feeding.cbtl --steps 1000 --eval-every 250
//     --eval-tasks 5` (seed 0). Target: under 10 s on one core.
#include "app/DomainSolverOptions.h"
#include "app/LoadedProgram.h"
#include "app/SimulatorFacts.h"
#include "bench/runtime/BenchPrograms.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Solver.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace cbtl;

const char* const kDomains[] = {"cleaning", "books", "feeding"};

app::LoadedProgram& program(const std::string& domain) { return bench::domainProgram(domain); }

approach::SimulatorFactory factory(const app::LoadedProgram& lp) {
  const auto facts = std::make_shared<domains::ProgramFacts>(app::simulatorFacts(lp));
  const std::string domain = lp.graph().domain;
  return [facts, domain](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator(domain, *facts, o, seed);
  };
}

void BM_RobotTrial(benchmark::State& state) {
  const std::string domain = kDomains[state.range(0)];
  const auto& lp = program(domain);
  approach::ExperimentConfig c;
  c.approach.kind = approach::ApproachKind::Cbtl;
  c.steps = 5000;
  c.evalEvery = 500;
  c.evalTasks = 10;
  c.solverOptions = app::domainSolverOptions(domain);
  double solved = 0, executed = 0, last = 0;
  for (auto _ : state) {
    const auto r = approach::runExperiment(lp, factory(lp), c);
    solved = r.train.solvedRate();
    executed = r.train.executedRate();
    last = r.evals.empty() ? 0 : r.evals.back().mean;
    benchmark::DoNotOptimize(last);
  }
  state.SetLabel(domain);
  state.counters["train_solved_rate"] = solved;
  state.counters["train_executed_rate"] = executed;
  state.counters["final_eval"] = last;
}
BENCHMARK(BM_RobotTrial)->DenseRange(0, 1)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RobotRequest(benchmark::State& state) {
  const std::string domain = kDomains[state.range(0)];
  auto& lp = program(domain);
  const auto makeWorld = factory(lp);
  model::UserModel user(lp.graph());
  solver::Solver solver(app::domainSolverOptions(domain), 1);
  std::uint64_t seed = 0;
  std::int64_t solved = 0;
  std::vector<double> ms;
  for (auto _ : state) {
    state.PauseTiming();
    const auto world = makeWorld({}, seed++ % 10);
    lp.syncWorld(*world);
    const std::size_t task = lp.taskFor(*world, 0);
    const auto obs = approach::observationVector(lp.program(), world->observe());
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    const approach::Plan plan = approach::makePlan(lp, task, obs, approach::evaluationChoice(), true, solver, user);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    solved += plan.ok ? 1 : 0;
  }
  std::sort(ms.begin(), ms.end());
  state.SetLabel(domain);
  state.counters["solved_rate"] = static_cast<double>(solved) / static_cast<double>(state.iterations());
  state.counters["median_ms"] = ms.empty() ? 0 : (ms[(ms.size() - 1) / 2] + ms[ms.size() / 2]) / 2;
}
BENCHMARK(BM_RobotRequest)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(20);

void BM_FeedingRun(benchmark::State& state) {
  const auto& lp = program("feeding");
  approach::ExperimentConfig c;
  c.approach.kind = approach::ApproachKind::Cbtl;
  c.steps = 1000;
  c.evalEvery = 250;
  c.evalTasks = 5;
  c.solverOptions = app::domainSolverOptions("feeding");
  double last = 0;
  for (auto _ : state) {
    const auto r = approach::runExperiment(lp, factory(lp), c);
    last = r.evals.empty() ? 0 : r.evals.back().mean;
    benchmark::DoNotOptimize(last);
  }
  state.counters["final_eval"] = last;
}
BENCHMARK(BM_FeedingRun)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
