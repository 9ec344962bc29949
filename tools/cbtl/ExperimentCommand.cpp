// `cbtl experiment FILE --approaches A,B --seeds 0..9 ...`: the same trial for several approaches and seeds,
// summarized as the paper reports it: mean and standard error over seeds of the evaluation satisfaction at
// every checkpoint (summary.csv), each preference's met rate where the domain judges preferences
// (preferences.csv), and tables on stdout. Exit codes: 0 ok, 1 bad input, 2 usage.
// Every trial writes its own run folder (OUT/<approach>/seed<S>, approach/RunDirectory.h); summary.csv is
// written last and atomically, so it is present only for a finished experiment. An OUT that holds a summary or
// any trial's files is refused unless --force (replace them) or --resume (finished trials are read back from
// their complete.json, interrupted ones continue from their last checkpoint, missing ones run).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"
#include "tools/cbtl/TrialPool.h"

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

// "0..9", "3", or "1,4,7"; seeds are unsigned, so a minus sign is refused (std::stoull would wrap it).
bool parseSeeds(const std::string& text, std::vector<std::uint64_t>& seeds) {
  if (text.find('-') != std::string::npos) return false;
  try {
    if (auto dots = text.find(".."); dots != std::string::npos) {
      const auto lo = std::stoull(text.substr(0, dots)), hi = std::stoull(text.substr(dots + 2));
      if (lo > hi || hi - lo > 10000) return false;
      for (auto s = lo; s <= hi; ++s) seeds.push_back(s);
      return true;
    }
    for (const auto& s : split(text, ',')) seeds.push_back(std::stoull(s));
    return !seeds.empty();
  } catch (...) {
    return false;
  }
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

struct Stat {
  double mean = 0, se = 0, sd = 0;
};
Stat stat(const std::vector<double>& v) {
  Stat s;
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  if (v.size() > 1) {
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
    s.se = s.sd / std::sqrt(static_cast<double>(v.size()));
  }
  return s;
}

std::string trialFolder(const std::string& out, cbtl::approach::ApproachKind kind, std::uint64_t seed) {
  return fmt::format("{}/{}/seed{}", out, cbtl::approach::toString(kind), seed);
}

// The met rate of each preference a domain judges (sim::StepResult::preferences): approach -> preference ->
// checkpoint -> one rate per seed that judged it there.
using PreferenceRates = std::map<std::string, std::map<std::string, std::map<std::int64_t, std::vector<double>>>>;

void addPreferenceRates(PreferenceRates& rates, const std::string& approach,
                        const cbtl::approach::ExperimentResult& r) {
  for (const auto& e : r.evals)
    for (const auto& [name, tally] : e.preferences)
      if (tally.judged > 0) rates[approach][name][e.step].push_back(tally.rate());
}

std::string preferencesCsv(const PreferenceRates& rates) {
  std::string csv = "approach,preference,training_step,seeds,met_rate_mean,met_rate_se\n";
  for (const auto& [approach, byName] : rates)
    for (const auto& [name, bySteps] : byName)
      for (const auto& [step, v] : bySteps) {
        const Stat m = stat(v);
        csv += fmt::format("{},{},{},{},{:.6g},{:.6g}\n", approach, name, step, v.size(), m.mean, m.se);
      }
  return csv;
}

// Per approach, each preference's met rate at the last checkpoint (mean ± standard deviation over seeds).
void printPreferenceTable(const PreferenceRates& rates, const std::vector<cbtl::approach::ApproachKind>& kinds) {
  if (rates.empty()) return;
  std::set<std::string> names;
  for (const auto& [approach, byName] : rates)
    for (const auto& [name, bySteps] : byName) names.insert(name);
  fmt::print("preferences met at the last checkpoint, per preference (mean ± standard deviation over seeds)\n");
  fmt::print("{:<20}", "approach");
  for (const auto& n : names) fmt::print(" {:>14}", n);
  fmt::print("\n");
  static const std::map<std::string, std::map<std::int64_t, std::vector<double>>> kNone;
  for (auto kind : kinds) {
    const auto it = rates.find(cbtl::approach::toString(kind));
    const auto& byName = it == rates.end() ? kNone : it->second;
    fmt::print("{:<20}", cbtl::approach::toString(kind));
    for (const auto& n : names) {
      const auto found = byName.find(n);
      if (found == byName.end() || found->second.empty()) {
        fmt::print(" {:>14}", "-");
        continue;
      }
      const Stat m = stat(found->second.rbegin()->second);
      fmt::print(" {:>14}", fmt::format("{:.2f} ± {:.2f}", m.mean, m.sd));
    }
    fmt::print("\n");
  }
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
      for (const auto& f : approach::runFilesIn(trialFolder(out, kind, seed))) {
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
  if (!parseSeeds(a.seeds, seeds)) {
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

  struct Summary {
    std::map<std::int64_t, std::vector<double>> bySteps, success, prefs;
    std::vector<double> meanOverCheckpoints, seconds;
    std::vector<double> finalSuccess, finalPrefs, finalPrefsWhenServed;  // per seed, at the last checkpoint
    approach::Competence train, eval;                                    // over every seed
  };
  std::map<std::string, Summary> summaries;
  std::int64_t rechecks = 0, refused = 0;
  std::string firstRefusal;
  cbtl::textpref::FaultReport llmFaults;  // over every trial
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
      if (!a.out.empty()) c.outDir = trialFolder(a.out, kind, seed);
      trials.push_back(std::move(c));
      labels.emplace_back(kind, seed);
    }
  }
  const auto outcomes = cli::runTrials(
      *lp, a.file, a.stdlibDir, a.text, a.external, trials, a.jobs, [&](std::size_t i, const cli::TrialOutcome& o) {
        if (a.quiet || o.error) return;
        fmt::print(stderr, "{} seed {}: mean eval {:+.3f}, final {:+.2f} ({:.2f} s)\n",
                   approach::toString(labels[i].first), labels[i].second, o.result.meanEval(),
                   o.result.evals.empty() ? 0.0 : o.result.evals.back().mean, o.seconds);
        if (o.result.llmFaults.any()) fmt::print(stderr, "{}", o.result.llmFaults.summary());
      });
  approach::Competence train, eval;
  PreferenceRates preferenceRates;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (outcomes[i].error) std::rethrow_exception(outcomes[i].error);
    const approach::ExperimentResult& r = outcomes[i].result;
    Summary& s = summaries[approach::toString(labels[i].first)];
    addPreferenceRates(preferenceRates, approach::toString(labels[i].first), r);
    llmFaults.add(r.llmFaults);
    s.seconds.push_back(outcomes[i].seconds);
    for (const auto& e : r.evals) {
      s.bySteps[e.step].push_back(e.mean);
      s.success[e.step].push_back(e.taskSuccessRate);
      s.prefs[e.step].push_back(e.preferencesMetRate);
    }
    s.meanOverCheckpoints.push_back(r.meanEval());
    s.train.add(r.train);
    s.eval.add(r.eval);
    train.add(r.train);
    eval.add(r.eval);
    rechecks += r.rechecks;
    if (r.recheckViolations > 0 && refused == 0) firstRefusal = r.firstRecheckViolation;
    refused += r.recheckViolations;
    if (!r.evals.empty()) {
      const auto& last = r.evals.back();
      s.finalSuccess.push_back(last.taskSuccessRate);
      s.finalPrefs.push_back(last.preferencesMetRate);
      if (last.taskSuccessRate > 0) s.finalPrefsWhenServed.push_back(last.preferencesMetRate / last.taskSuccessRate);
    }
  }
  if (!a.out.empty()) {
    std::string csv = "approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean\n";
    for (const auto& [name, s] : summaries) {
      for (const auto& [step, v] : s.bySteps) {
        const Stat m = stat(v);
        csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", name, step, v.size(), m.mean, m.se,
                           stat(s.success.at(step)).mean, stat(s.prefs.at(step)).mean);
      }
    }
    approach::writeFileAtomic((std::filesystem::path(a.out) / "summary.csv").string(), csv);
    if (!preferenceRates.empty())
      approach::writeFileAtomic((std::filesystem::path(a.out) / "preferences.csv").string(),
                                preferencesCsv(preferenceRates));
  }
  // The table: selected checkpoints (or --columns), the mean over all checkpoints, the last checkpoint's
  // task success and preferences met, and the time per trial.
  std::vector<std::int64_t> cols;
  if (!a.columns.empty()) {
    cols = requestedColumns;
  } else {
    for (std::int64_t c : {std::int64_t{0}, a.steps / 20, a.steps / 10, a.steps / 4, a.steps / 2, a.steps}) {
      const std::int64_t snapped = (c / a.evalEvery) * a.evalEvery;
      if (std::find(cols.begin(), cols.end(), snapped) == cols.end()) cols.push_back(snapped);
    }
    if (cols.back() != a.steps) cols.push_back(a.steps);
  }
  fmt::print("eval satisfaction, mean ± standard error over {} seed{} ({} tasks per checkpoint)\n", seeds.size(),
             seeds.size() == 1 ? "" : "s", a.evalTasks);
  fmt::print("{:<20}", "approach");
  for (auto c : cols) fmt::print(" {:>14}", fmt::format("step {}", c));
  fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8}\n", "all checkpts", "success", "prefs met", "met|served", "s/trial");
  for (auto kind : kinds) {
    const Summary& s = summaries.at(approach::toString(kind));
    fmt::print("{:<20}", approach::toString(kind));
    for (auto c : cols) {
      auto it = s.bySteps.find(c);
      if (it == s.bySteps.end())
        fmt::print(" {:>14}", "-");
      else {
        const Stat m = stat(it->second);
        fmt::print(" {:>14}", fmt::format("{:+.2f} ± {:.2f}", m.mean, m.se));
      }
    }
    const Stat all = stat(s.meanOverCheckpoints);
    const Stat success = stat(s.finalSuccess), prefs = stat(s.finalPrefs), served = stat(s.finalPrefsWhenServed);
    fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8.2f}\n", fmt::format("{:+.3f} ± {:.3f}", all.mean, all.se),
               fmt::format("{:.2f} ± {:.2f}", success.mean, success.sd),
               fmt::format("{:.2f} ± {:.2f}", prefs.mean, prefs.sd),
               fmt::format("{:.2f} ± {:.2f}", served.mean, served.sd), stat(s.seconds).mean);
  }
  fmt::print(
      "columns: eval satisfaction per checkpoint and over all checkpoints (mean ± standard error over seeds); task\n"
      "success, preferences met (of all tasks) and preferences met of the served meals at the last checkpoint\n"
      "(mean ± standard deviation over seeds); wall-clock seconds per trial\n");
  printPreferenceTable(preferenceRates, kinds);
  fmt::print(
      "competence over every seed: requests solved within budget, solved plans executed without a failed "
      "action, dry-run mismatches\n");
  fmt::print("{:<20} {:>22} {:>22} {:>22} {:>22} {:>10}\n", "approach", "train solved", "train executed", "eval solved",
             "eval executed", "mismatch");
  const auto rate = [](std::int64_t n, std::int64_t d) {
    return fmt::format("{}/{} ({:.1f}%)", n, d,
                       d > 0 ? 100.0 * static_cast<double>(n) / static_cast<double>(d) : 100.0);
  };
  for (auto kind : kinds) {
    const Summary& s = summaries.at(approach::toString(kind));
    fmt::print("{:<20} {:>22} {:>22} {:>22} {:>22} {:>10}\n", approach::toString(kind),
               rate(s.train.solved, s.train.requests), rate(s.train.executed, s.train.executed + s.train.failed),
               rate(s.eval.solved, s.eval.requests), rate(s.eval.executed, s.eval.executed + s.eval.failed),
               s.train.dryRunMismatches + s.eval.dryRunMismatches);
  }
  fmt::print("{} solutions re-checked before execution, {} refused\n", rechecks, refused);
  cli::printLlmFaults(stdout, llmFaults);
  if (!a.out.empty()) fmt::print("wrote {}/summary.csv and one folder per approach and seed\n", a.out);
  if (refused > 0) {
    fmt::print(stderr,
               "cbtl experiment: internal error: {} accepted solutions failed the independent re-check and were "
               "refused; the first: {}\n",
               refused, firstRefusal);
    return 70;
  }
  return 0;
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
