// `cbtl experiment FILE --approaches A,B --seeds 0..9 ...`: the same trial for several approaches and seeds,
// summarized as the paper reports it: mean and standard error over seeds of the evaluation satisfaction at
// every checkpoint (summary.csv), each preference's met rate where the domain judges preferences
// (preferences.csv), and tables on stdout. Exit codes: 0 ok, 1 bad input, 2 usage, 3 an approach's requests failed
// more often than --max-failure-rate allows (app/RunFailures.h).
// Every trial writes its own run folder (OUT/<approach>/seed<S>, approach/RunDirectory.h); summary.csv is
// written last and atomically, so it is present only for a finished experiment. An OUT that holds a summary or
// any trial's files is refused unless --force (replace them) or --resume (finished trials are read back from
// their complete.json, interrupted ones continue from their last checkpoint, missing ones run).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/ExperimentReport.h"
#include "tools/cbtl/Interrupt.h"
#include "tools/cbtl/RuntimeSupport.h"
#include "tools/cbtl/TrialPool.h"
#include "tools/cbtl/TrialProgress.h"

#include "app/sweep/SweepConfig.h"
#include "runtime/approach/RunDirectory.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

namespace {

struct ExperimentArgs : cbtl::cli::TrialArgs {
  std::string approaches = "cbtl,no-personalization", seeds = "0..9", out, columns;
  bool quiet = false, force = false, resume = false, participantFromSeed = false;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// "--columns 0,500,1000": training steps >= 0; anything else is a usage error naming the option.
std::vector<std::int64_t> parseColumns(const std::string& text) {
  std::vector<std::int64_t> cols;
  for (const auto& c : split(text, ',')) {
    std::size_t used = 0;
    std::int64_t v = -1;
    try {
      v = std::stoll(c, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != c.size() || v < 0)
      throw cbtl::cli::UsageError(fmt::format("--columns wants comma-separated training steps >= 0, not '{}'", c));
    cols.push_back(v);
  }
  return cols;
}

// Locks OUT for the whole experiment and applies the mode to what the experiment would write: Fresh refuses
// an OUT with summary.csv or any trial's files, Force removes summary.csv (each trial clears its own folder).
std::unique_ptr<cbtl::approach::DirectoryLock> prepareOut(const std::string& out,
                                                          const std::vector<cbtl::approach::ApproachKind>& kinds,
                                                          const std::vector<std::uint64_t>& seeds,
                                                          cbtl::approach::RunMode mode) {
  using namespace cbtl;
  if (out.empty()) return nullptr;
  std::filesystem::create_directories(out);
  auto lock = std::make_unique<approach::DirectoryLock>(out);
  std::vector<std::string> existing;
  for (const char* name : {"summary.csv", "preferences.csv"})
    if (std::filesystem::exists(std::filesystem::path(out) / name)) existing.push_back(name);
  for (auto kind : kinds) {
    for (auto seed : seeds) {
      for (const auto& f : approach::runFilesIn(cbtl::cli::trialFolder(out, kind, seed))) {
        existing.push_back(fmt::format("{}/seed{}/{}", approach::toString(kind), seed, f));
      }
    }
  }
  if (!existing.empty() && mode == approach::RunMode::Fresh)
    throw approach::RunDirectoryError(approach::refusalMessage(out, existing));
  if (mode == approach::RunMode::Force) {
    std::filesystem::remove(std::filesystem::path(out) / "summary.csv");
    std::filesystem::remove(std::filesystem::path(out) / "preferences.csv");
  }
  return lock;
}

int runExperiments(const ExperimentArgs& a) {
  using namespace cbtl;
  std::vector<approach::ApproachKind> kinds;
  for (const auto& name : split(a.approaches, ',')) {
    const auto k = approach::parseApproach(name);
    if (!k) {
      fmt::print(stderr, "cbtl experiment: error: unknown approach '{}'\n", name);
      return 2;
    }
    kinds.push_back(*k);
  }
  const std::vector<std::int64_t> requestedColumns =
      parseColumns(a.columns);  // before the trials: a typo costs nothing
  std::vector<std::uint64_t> seeds;
  if (!cbtl::sweep::parseSeedList(a.seeds, seeds)) {
    fmt::print(stderr, "cbtl experiment: error: --seeds wants 'LO..HI' or a comma-separated list, not '{}'\n", a.seeds);
    return 2;
  }
  approach::ExperimentConfig base;
  if (!cli::configureTrial("experiment", a, base)) return 2;
  auto lp = cli::loadForRun("experiment", a.file, a.stdlibDir);
  if (!lp) return 1;
  base.solverOptions = cli::solverOptionsFor(a.solver, lp->graph().domain);
  if (!cli::domainSimulator("experiment", *lp, base.simulator, a.external)) return 1;  // says which domains exist
  base.runMode = a.force ? approach::RunMode::Force : a.resume ? approach::RunMode::Resume : approach::RunMode::Fresh;
  base.testHook = approach::killHookFromEnvironment();
  const auto lock = prepareOut(a.out, kinds, seeds, base.runMode);

  // Every trial's configuration, in the table's order; they run on --jobs threads (TrialPool.h).
  std::vector<approach::ExperimentConfig> trials;
  std::vector<std::pair<approach::ApproachKind, std::uint64_t>> labels;
  for (auto kind : kinds) {
    for (auto seed : seeds) {
      approach::ExperimentConfig c = base;
      c.approach.kind = kind;
      c.seed = seed;
      if (a.participantFromSeed) c.simulator.participant = static_cast<std::int64_t>(seed);
      c.progress = false;
      if (!a.out.empty()) c.outDir = cbtl::cli::trialFolder(a.out, kind, seed);
      trials.push_back(std::move(c));
      labels.emplace_back(kind, seed);
    }
  }
  cli::sayOnInterrupt(cli::interruptMessage(
      "experiment", a.out, "every finished trial, and each unfinished one up to its last checkpoint,"));
  // On a terminal: how many trials are done and about how long the rest takes (from the trials timed so far).
  const bool terminal = !a.quiet && ::isatty(STDERR_FILENO) != 0;
  cli::TrialProgress progress(trials.size());
  if (terminal)
    fmt::print(stderr, "{} trials ({} approach{} x {} seed{}) on {} job{}\n", trials.size(), kinds.size(),
               kinds.size() == 1 ? "" : "es", seeds.size(), seeds.size() == 1 ? "" : "s", a.jobs,
               a.jobs == 1 ? "" : "s");
  const auto outcomes = cli::runTrials(
      *lp, a.file, a.stdlibDir, a.text, a.external, trials, a.jobs, [&](std::size_t i, const cli::TrialOutcome& o) {
        const std::string line =
            progress.finished(fmt::format("{} seed {}", approach::toString(labels[i].first), labels[i].second),
                              o.seconds, !o.finishedEarlier);
        if (a.quiet || o.error) return;
        fmt::print(stderr, "{} seed {}: mean eval {:+.3f}, final {:+.2f} ({})\n", approach::toString(labels[i].first),
                   labels[i].second, o.result.meanEval(), o.result.evals.empty() ? 0.0 : o.result.evals.back().mean,
                   o.finishedEarlier ? (o.seconds > 0 ? fmt::format("finished earlier, {:.2f} s", o.seconds)
                                                      : std::string("finished earlier"))
                                     : fmt::format("{:.2f} s", o.seconds));
        if (o.result.llmFaults.any()) fmt::print(stderr, "{}", o.result.llmFaults.summary());
        if (terminal) fmt::print(stderr, "{}\n", line);
      });
  std::vector<cli::TrialRecord> records;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (outcomes[i].error) std::rethrow_exception(outcomes[i].error);
    records.push_back(cli::TrialRecord{labels[i].first, labels[i].second, &outcomes[i].result, outcomes[i].seconds});
  }
  const int code = cli::reportExperiment(
      "experiment", kinds, seeds.size(), records,
      cli::ReportColumns{requestedColumns, !a.columns.empty(), a.steps, a.evalEvery, a.evalTasks}, a.out);
  if (code != 0) return code;
  return cli::checkFailureRates("experiment", a.file, kinds, records, a.maxFailureRate);
}

void addExperiment(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* cmd =
      app.add_subcommand("experiment", "run approaches x seeds and summarize (mean ± standard error over seeds)");
  cbtl::cli::addTrialOptions(cmd, *args);
  cmd->add_option("--approaches", args->approaches, "comma-separated approaches")->capture_default_str();
  cmd->add_option("--seeds", args->seeds, "LO..HI or a comma-separated list")->capture_default_str();
  cmd->add_option("--columns", args->columns, "checkpoints to show in the table, comma-separated");
  cmd->add_flag("--participant-from-seed", args->participantFromSeed,
                "each seed's trial has its own simulated participant, the seed's (Feeding: --seeds 0..59 is 60 people)")
      ->excludes("--participant");
  cmd->add_option("--out", args->out, "write every trial's files and summary.csv here");
  cmd->add_flag("--quiet,-q", args->quiet, "no per-trial lines");
  cmd->add_option("--jobs,-j", args->jobs, "trials run in parallel (results equal a serial run's)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  auto* force =
      cmd->add_flag("--force", args->force, "replace the experiment already in --out (only the files runs write)");
  cmd->add_flag("--resume", args->resume,
                "continue the experiment in --out: finished trials are kept, the others resume")
      ->excludes(force);
  cmd->callback(
      [args, &exitCode]() { cbtl::cli::runCommand("experiment", exitCode, [&] { return runExperiments(*args); }); });
}

const cbtl::cli::RegisterCommand registerExperiment(15, addExperiment);

}  // namespace
