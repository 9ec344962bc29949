#include "tools/cbtl/ExperimentReport.h"

#include "app/RunFailures.h"

#include "runtime/approach/RunDirectory.h"
#include "tools/cbtl/RuntimeSupport.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace cbtl::cli {

namespace {

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

// The met rate of each preference a domain judges (sim::StepResult::preferences): approach -> preference ->
// checkpoint -> one rate per seed that judged it there.
using PreferenceRates = std::map<std::string, std::map<std::string, std::map<std::int64_t, std::vector<double>>>>;

void addPreferenceRates(PreferenceRates& rates, const std::string& approachName, const approach::ExperimentResult& r) {
  for (const auto& e : r.evals)
    for (const auto& [name, tally] : e.preferences)
      if (tally.judged > 0) rates[approachName][name][e.step].push_back(tally.rate());
}

std::string preferencesCsv(const PreferenceRates& rates) {
  std::string csv = "approach,preference,training_step,seeds,met_rate_mean,met_rate_se\n";
  for (const auto& [approachName, byName] : rates)
    for (const auto& [name, bySteps] : byName)
      for (const auto& [step, v] : bySteps) {
        const Stat m = stat(v);
        csv += fmt::format("{},{},{},{},{:.6g},{:.6g}\n", approachName, name, step, v.size(), m.mean, m.se);
      }
  return csv;
}

// Per approach, each preference's met rate at the last checkpoint (mean ± standard deviation over seeds).
void printPreferenceTable(const PreferenceRates& rates, const std::vector<approach::ApproachKind>& kinds) {
  if (rates.empty()) return;
  std::set<std::string> names;
  for (const auto& [approachName, byName] : rates)
    for (const auto& [name, bySteps] : byName) names.insert(name);
  fmt::print("preferences met at the last checkpoint, per preference (mean ± standard deviation over seeds)\n");
  fmt::print("{:<20}", "approach");
  for (const auto& n : names) fmt::print(" {:>14}", n);
  fmt::print("\n");
  static const std::map<std::string, std::map<std::int64_t, std::vector<double>>> kNone;
  for (auto kind : kinds) {
    const auto it = rates.find(approach::toString(kind));
    const auto& byName = it == rates.end() ? kNone : it->second;
    fmt::print("{:<20}", approach::toString(kind));
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

}  // namespace

std::string trialFolder(const std::string& out, approach::ApproachKind kind, std::uint64_t seed) {
  return fmt::format("{}/{}/seed{}", out, approach::toString(kind), seed);
}

int checkFailureRates(const std::string& command, const std::string& file,
                      const std::vector<approach::ApproachKind>& kinds, const std::vector<TrialRecord>& trials,
                      double maxRate) {
  std::vector<app::PhaseFailures> phases;
  for (auto kind : kinds) {
    approach::Competence train, eval;
    for (const TrialRecord& r : trials) {
      if (r.kind != kind) continue;
      train.add(r.result->train);
      eval.add(r.result->eval);
    }
    phases.push_back(app::phaseFailures(fmt::format("{} training", approach::toString(kind)), train));
    phases.push_back(app::evaluationFailures(fmt::format("{} evaluation", approach::toString(kind)), eval));
  }
  const auto above = app::phasesAbove(phases, maxRate);
  if (above.empty()) return 0;
  fmt::print(stderr, "{}", app::failureWarning(command, file, above, maxRate));
  return 3;
}

int reportExperiment(const std::string& command, const std::vector<approach::ApproachKind>& kinds,
                     std::size_t seedCount, const std::vector<TrialRecord>& trials, const ReportColumns& columns,
                     const std::string& out) {
  struct Summary {
    std::map<std::int64_t, std::vector<double>> bySteps, success, prefs;
    std::vector<double> meanOverCheckpoints, seconds;
    std::vector<double> finalSuccess, finalPrefs, finalPrefsWhenServed;  // per seed, at the last checkpoint
    approach::Competence train, eval;                                    // over every seed
  };
  std::map<std::string, Summary> summaries;
  std::int64_t rechecks = 0, refused = 0;
  std::string firstRefusal;
  textpref::FaultReport llmFaults;  // over every trial
  approach::Competence train, eval;
  PreferenceRates preferenceRates;
  for (const TrialRecord& trial : trials) {
    const approach::ExperimentResult& r = *trial.result;
    Summary& s = summaries[approach::toString(trial.kind)];
    addPreferenceRates(preferenceRates, approach::toString(trial.kind), r);
    llmFaults.add(r.llmFaults);
    s.seconds.push_back(trial.seconds);
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
  if (!out.empty()) {
    std::string csv = "approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean\n";
    for (const auto& [name, s] : summaries) {
      for (const auto& [step, v] : s.bySteps) {
        const Stat m = stat(v);
        csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", name, step, v.size(), m.mean, m.se,
                           stat(s.success.at(step)).mean, stat(s.prefs.at(step)).mean);
      }
    }
    approach::writeFileAtomic((std::filesystem::path(out) / "summary.csv").string(), csv);
    if (!preferenceRates.empty())
      approach::writeFileAtomic((std::filesystem::path(out) / "preferences.csv").string(),
                                preferencesCsv(preferenceRates));
  }
  // The table: selected checkpoints (or --columns), the mean over all checkpoints, the last checkpoint's
  // task success and preferences met, and the time per trial.
  std::vector<std::int64_t> cols;
  if (columns.given) {
    cols = columns.steps;
  } else {
    for (std::int64_t c : {std::int64_t{0}, columns.trainingSteps / 20, columns.trainingSteps / 10,
                           columns.trainingSteps / 4, columns.trainingSteps / 2, columns.trainingSteps}) {
      const std::int64_t snapped = (c / columns.evalEvery) * columns.evalEvery;
      if (std::find(cols.begin(), cols.end(), snapped) == cols.end()) cols.push_back(snapped);
    }
    if (cols.back() != columns.trainingSteps) cols.push_back(columns.trainingSteps);
  }
  fmt::print("eval satisfaction, mean ± standard error over {} seed{} ({} tasks per checkpoint)\n", seedCount,
             seedCount == 1 ? "" : "s", columns.evalTasks);
  fmt::print("{:<20}", "approach");
  for (auto c : cols) fmt::print(" {:>14}", fmt::format("step {}", c));
  fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8}\n", "all checkpts", "success", "prefs met", "met|served", "s/trial");
  // Which spread each column shows, under its heading: the table mixes them (see the legend below it).
  fmt::print("{:<20}", "");
  for (std::size_t i = 0; i < cols.size(); ++i) fmt::print(" {:>14}", "mean ± s.e.");
  fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8}\n", "mean ± s.e.", "mean ± s.d.", "mean ± s.d.", "mean ± s.d.",
             "mean");
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
    // A trial read back from its folder has the time its timing.json recorded, or 0 when an earlier cbtl wrote none:
    // "-" when no trial has a time, else the mean of those that have one.
    std::vector<double> timedSeconds;
    for (double x : s.seconds)
      if (x > 0) timedSeconds.push_back(x);
    const bool timed = !timedSeconds.empty();
    fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8}\n", fmt::format("{:+.3f} ± {:.3f}", all.mean, all.se),
               fmt::format("{:.2f} ± {:.2f}", success.mean, success.sd),
               fmt::format("{:.2f} ± {:.2f}", prefs.mean, prefs.sd),
               fmt::format("{:.2f} ± {:.2f}", served.mean, served.sd),
               timed ? fmt::format("{:.2f}", stat(timedSeconds).mean) : std::string("-"));
  }
  fmt::print(
      "columns: eval satisfaction per checkpoint and over all checkpoints (mean ± standard error over seeds); task\n"
      "success, preferences met (of all tasks) and preferences met of the tasks done (met|served) at the last\n"
      "checkpoint (mean ± standard deviation over seeds); wall-clock seconds per trial\n");
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
  if (!out.empty()) fmt::print("wrote {}/summary.csv and one folder per approach and seed\n", out);
  if (refused > 0) {
    fmt::print(stderr,
               "cbtl {}: internal error: {} accepted solutions failed the independent re-check and were "
               "refused; the first: {}\n",
               command, refused, firstRefusal);
    return 70;
  }
  return 0;
}

}  // namespace cbtl::cli
