#include "tools/cbtl/SweepRunner.h"

#include "app/plot/Chart.h"
#include "app/plot/ResultsFigure.h"
#include "app/plot/SummaryTable.h"
#include "runtime/approach/RunDirectory.h"
#include "tools/cbtl/ExperimentReport.h"

#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

namespace cbtl::cli {

namespace {

namespace fs = std::filesystem;

// What one thread keeps between trials: the programs it loaded and their simulator factories, and a text backend
// per experiment (each counts its own faults).
struct WorkerCache {
  std::map<std::string, std::unique_ptr<app::LoadedProgram>> programs;
  std::map<std::size_t, approach::SimulatorFactory> factories;
  std::map<std::size_t, std::shared_ptr<const textpref::TextBackend>> backends;

  const app::LoadedProgram& program(const std::string& path, const std::string& stdlibDir) {
    auto& lp = programs[path];
    if (!lp) {
      lp = app::LoadedProgram::load(path, stdlibDir);
      if (!lp->ok()) throw std::runtime_error("the program cannot be loaded again: " + lp->errors());
    }
    return *lp;
  }
};

// The configuration of trial `t`, ready to run with `lp`.
approach::ExperimentConfig trialConfig(const sweep::SweepTrial& t, const PreparedExperiment& p,
                                       const app::LoadedProgram& lp) {
  approach::ExperimentConfig c = p.base;
  c.solverOptions = solverOptionsFor(p.args.solver, lp.graph().domain);
  c.approach.kind = *approach::parseApproach(t.approach);  // checked by prepareSweep
  c.seed = t.seed;
  c.outDir = t.dir;
  c.runMode = approach::RunMode::Resume;
  c.progress = false;
  return c;
}

approach::ExperimentResult runOne(const sweep::SweepPlan& plan, const std::vector<PreparedExperiment>& prepared,
                                  std::size_t index, WorkerCache& cache) {
  const sweep::SweepTrial& t = plan.trials[index];
  const PreparedExperiment& p = prepared[t.experiment];
  const app::LoadedProgram& lp = cache.program(plan.experiments[t.experiment].program, p.args.stdlibDir);
  auto factory = cache.factories.find(t.experiment);
  if (factory == cache.factories.end())
    factory = cache.factories.emplace(t.experiment, simulatorFactory(lp, p.args.external)).first;
  auto backend = cache.backends.find(t.experiment);
  if (backend == cache.backends.end()) {
    const auto made = makeTextBackend("sweep", p.args.text);
    if (!made) throw std::runtime_error("the text backend cannot be made");
    backend = cache.backends.emplace(t.experiment, *made).first;
  }
  approach::ExperimentConfig c = trialConfig(t, p, lp);
  c.textBackend = backend->second;
  return approach::runExperiment(lp, factory->second, c);
}

std::string describe(std::exception_ptr e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "an unknown exception";
  }
}

}  // namespace

std::vector<PreparedExperiment> prepareSweep(const sweep::SweepConfig& config, const sweep::SweepPlan& plan) {
  std::vector<PreparedExperiment> out;
  std::map<std::string, std::unique_ptr<app::LoadedProgram>> loaded;
  for (const sweep::PlannedExperiment& x : plan.experiments) {
    const std::string where = fmt::format("{}: {} ({})", config.path, x.where, x.name);
    PreparedExperiment p;
    CLI::App parser("a sweep's trial", "sweep");
    addTrialOptions(&parser, p.args);
    std::vector<std::string> argv = x.arguments;
    argv.insert(argv.begin(), x.program);
    std::reverse(argv.begin(), argv.end());  // CLI11 takes them last first
    try {
      parser.parse(argv);
    } catch (const CLI::ParseError& e) {
      throw sweep::SweepError(fmt::format("{}: options: {}", where, e.what()));
    }
    if (!configureTrial("sweep", p.args, p.base)) throw sweep::SweepError(where + ": options: see the error above");
    p.base.testHook = approach::killHookFromEnvironment();
    for (const auto& name : x.approaches) {
      const auto kind = approach::parseApproach(name);
      if (!kind)
        throw sweep::SweepError(
            fmt::format("{}: unknown approach '{}' (cbtl, no-personalization, free-explore, "
                        "exploit-only, epsilon-greedy)",
                        where, name));
      p.kinds.push_back(*kind);
    }
    auto& lp = loaded[x.program];
    if (!lp) {
      lp = loadForRun("sweep", x.program, p.args.stdlibDir);
      if (!lp) throw sweep::SweepError(where + ": the program cannot be run (its diagnostics are above)");
    }
    if (!domainSimulator("sweep", *lp, p.base.simulator, p.args.external))
      throw sweep::SweepError(where + ": no simulator for the program");
    out.push_back(std::move(p));
  }
  return out;
}

std::size_t runSweepTrials(const sweep::SweepPlan& plan, const std::vector<PreparedExperiment>& prepared,
                           const std::vector<std::size_t>& indices, int jobs,
                           const std::function<void(const TrialEvent&)>& onDone) {
  std::mutex doneMutex;
  std::size_t failures = 0;
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    WorkerCache cache;
    for (std::size_t k = next++; k < indices.size(); k = next++) {
      TrialEvent event;
      event.trial = indices[k];
      const auto start = std::chrono::steady_clock::now();
      try {
        runOne(plan, prepared, indices[k], cache);
      } catch (...) {
        event.failed = true;
        event.error = describe(std::current_exception());
      }
      event.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard lock(doneMutex);
      failures += event.failed ? 1 : 0;
      onDone(event);
    }
  };
  jobs = std::max(1, std::min<int>(jobs, static_cast<int>(indices.size())));
  std::vector<std::thread> pool;
  for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return failures;
}

int collectSweep(const sweep::SweepConfig& config, const sweep::SweepPlan& plan,
                 const std::vector<PreparedExperiment>& prepared, const std::map<std::size_t, double>& seconds) {
  int exitCode = 0;
  std::vector<bool> collected(plan.experiments.size(), false);
  for (std::size_t e = 0; e < plan.experiments.size(); ++e) {
    const sweep::PlannedExperiment& x = plan.experiments[e];
    std::size_t unfinished = 0;
    for (std::size_t i : x.trials) unfinished += sweep::trialComplete(plan.trials[i]) ? 0 : 1;
    if (unfinished > 0) {
      fmt::print(stderr, "cbtl sweep: {}: {} of {} trials not finished (run the sweep again to finish them)\n", x.name,
                 unfinished, x.trials.size());
      exitCode = 1;
      continue;
    }
    // A finished trial is read back from its folder (--resume of a complete run reruns nothing).
    WorkerCache cache;
    std::vector<approach::ExperimentResult> results;
    results.reserve(x.trials.size());
    for (std::size_t i : x.trials) results.push_back(runOne(plan, prepared, i, cache));
    std::vector<TrialRecord> records;
    for (std::size_t k = 0; k < x.trials.size(); ++k) {
      const sweep::SweepTrial& t = plan.trials[x.trials[k]];
      const auto timed = seconds.find(t.index);
      records.push_back(TrialRecord{*approach::parseApproach(t.approach), t.seed, &results[k],
                                    timed == seconds.end() ? 0.0 : timed->second});
    }
    fmt::print("== {}\n", x.name);
    const ReportColumns columns{x.columns, !x.columns.empty(), prepared[e].args.steps, prepared[e].args.evalEvery,
                                prepared[e].args.evalTasks};
    int code = reportExperiment("sweep", prepared[e].kinds, x.seeds.size(), records, columns, x.dir);
    // Its options' --max-failure-rate (default 0.10), per experiment: a stuck experiment is not a result.
    if (code == 0)
      code = checkFailureRates(fmt::format("sweep: {}", x.name), prepared[e].args.file, prepared[e].kinds, records,
                               prepared[e].args.maxFailureRate);
    exitCode = std::max(exitCode, code);
    collected[e] = true;
  }
  for (const sweep::PlotSpec& p : config.plots) {
    plot::FigureRequest r = p.request;
    bool ready = true;
    for (const auto& name : p.results)
      for (std::size_t e = 0; e < plan.experiments.size(); ++e)
        if (plan.experiments[e].name == name) {
          ready = ready && collected[e];
          r.results.push_back(plan.experiments[e].dir);
        }
    const std::string out = (fs::path(plan.out) / p.out).string();
    if (!ready) {
      fmt::print(stderr, "cbtl sweep: {}: not drawn: some of its experiments are not finished\n", out);
      exitCode = std::max(exitCode, 1);
      continue;
    }
    try {
      fs::create_directories(fs::path(out).parent_path());
      plot::renderFigure(plot::figureFromResults(r), out);
      fmt::print("wrote {}\n", out);
    } catch (const std::exception& e) {
      fmt::print(stderr, "cbtl sweep: {}: {}: {}\n", config.path, p.where, e.what());
      exitCode = std::max(exitCode, 1);
    }
  }
  return exitCode;
}

}  // namespace cbtl::cli
