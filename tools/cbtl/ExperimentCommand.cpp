// `cbtl experiment FILE --approaches A,B --seeds 0..9 ...`: the same trial for several approaches and seeds,
// summarized as the paper reports it: mean and standard error over seeds of the evaluation satisfaction at
// every checkpoint (summary.csv), and a table on stdout. Exit codes: 0 ok, 1 bad input, 2 usage.
#include "CommandRegistry.h"
#include "RuntimeSupport.h"

#include "UserModel.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace {

struct ExperimentArgs : cbtl::cli::TrialArgs {
  std::string approaches = "cbtl,no-personalization", seeds = "0..9", out, columns;
  bool quiet = false;
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

// "0..9", "3", or "1,4,7".
bool parseSeeds(const std::string& text, std::vector<std::uint64_t>& seeds) {
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
  std::vector<std::uint64_t> seeds;
  if (!parseSeeds(a.seeds, seeds)) {
    fmt::print(stderr, "cbtl experiment: error: --seeds wants 'LO..HI' or a comma-separated list, not '{}'\n", a.seeds);
    return 2;
  }
  approach::ExperimentConfig base;
  if (!cli::configureTrial("experiment", a, base)) return 2;
  auto lp = cli::loadForRun("experiment", a.file, a.stdlibDir);
  if (!lp) return 1;
  const auto factoryOrNone = cli::domainSimulator("experiment", *lp, base.simulator);
  if (!factoryOrNone) return 1;
  const approach::SimulatorFactory& factory = *factoryOrNone;

  struct Summary {
    std::map<std::int64_t, std::vector<double>> bySteps, success, prefs;
    std::vector<double> meanOverCheckpoints, seconds;
    std::vector<double> finalSuccess, finalPrefs, finalPrefsWhenServed;  // per seed, at the last checkpoint
  };
  std::map<std::string, Summary> summaries;
  cbtl::textpref::FaultReport llmFaults;  // over every trial
  for (auto kind : kinds) {
    Summary& s = summaries[approach::toString(kind)];
    for (auto seed : seeds) {
      approach::ExperimentConfig c = base;
      c.approach.kind = kind;
      c.seed = seed;
      if (!a.out.empty()) c.outDir = fmt::format("{}/{}/seed{}", a.out, approach::toString(kind), seed);
      const auto start = std::chrono::steady_clock::now();
      const auto r = approach::runExperiment(*lp, factory, c);
      llmFaults.add(r.llmFaults);
      s.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      for (const auto& e : r.evals) {
        s.bySteps[e.step].push_back(e.mean);
        s.success[e.step].push_back(e.taskSuccessRate);
        s.prefs[e.step].push_back(e.preferencesMetRate);
      }
      s.meanOverCheckpoints.push_back(r.meanEval());
      if (!r.evals.empty()) {
        const auto& last = r.evals.back();
        s.finalSuccess.push_back(last.taskSuccessRate);
        s.finalPrefs.push_back(last.preferencesMetRate);
        if (last.taskSuccessRate > 0) s.finalPrefsWhenServed.push_back(last.preferencesMetRate / last.taskSuccessRate);
      }
      if (!a.quiet) {
        fmt::print(stderr, "{} seed {}: mean eval {:+.3f}, final {:+.2f} ({:.2f} s)\n", approach::toString(kind), seed, r.meanEval(),
                   r.evals.empty() ? 0.0 : r.evals.back().mean, s.seconds.back());
        if (r.llmFaults.any()) fmt::print(stderr, "{}", r.llmFaults.summary());
      }
    }
  }
  if (!a.out.empty()) {
    std::filesystem::create_directories(a.out);
    std::ofstream csv(std::filesystem::path(a.out) / "summary.csv");
    csv << "approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean\n";
    for (const auto& [name, s] : summaries) {
      for (const auto& [step, v] : s.bySteps) {
        const Stat m = stat(v);
        csv << fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", name, step, v.size(), m.mean, m.se, stat(s.success.at(step)).mean,
                           stat(s.prefs.at(step)).mean);
      }
    }
  }
  // The table: selected checkpoints (or --columns), the mean over all checkpoints, the last checkpoint's
  // task success and preferences met, and the time per trial.
  std::vector<std::int64_t> cols;
  if (!a.columns.empty()) {
    for (const auto& c : split(a.columns, ',')) cols.push_back(std::stoll(c));
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
      if (it == s.bySteps.end()) fmt::print(" {:>14}", "-");
      else {
        const Stat m = stat(it->second);
        fmt::print(" {:>14}", fmt::format("{:+.2f} ± {:.2f}", m.mean, m.se));
      }
    }
    const Stat all = stat(s.meanOverCheckpoints);
    const Stat success = stat(s.finalSuccess), prefs = stat(s.finalPrefs), served = stat(s.finalPrefsWhenServed);
    fmt::print(" {:>14} {:>12} {:>12} {:>12} {:>8.2f}\n", fmt::format("{:+.3f} ± {:.3f}", all.mean, all.se),
               fmt::format("{:.2f} ± {:.2f}", success.mean, success.sd), fmt::format("{:.2f} ± {:.2f}", prefs.mean, prefs.sd),
               fmt::format("{:.2f} ± {:.2f}", served.mean, served.sd), stat(s.seconds).mean);
  }
  fmt::print("columns: eval satisfaction per checkpoint and over all checkpoints (mean ± standard error over seeds); task\n"
             "success, preferences met (of all tasks) and preferences met of the served meals at the last checkpoint\n"
             "(mean ± standard deviation over seeds); wall-clock seconds per trial\n");
  cli::printLlmFaults(stdout, llmFaults);
  if (!a.out.empty()) fmt::print("wrote {}/summary.csv and one folder per approach and seed\n", a.out);
  return 0;
}

void addExperiment(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* cmd = app.add_subcommand("experiment", "run approaches x seeds and summarize (mean ± standard error over seeds)");
  cbtl::cli::addTrialOptions(cmd, *args);
  cmd->add_option("--approaches", args->approaches, "comma-separated approaches")->capture_default_str();
  cmd->add_option("--seeds", args->seeds, "LO..HI or a comma-separated list")->capture_default_str();
  cmd->add_option("--columns", args->columns, "checkpoints to show in the table, comma-separated");
  cmd->add_option("--out", args->out, "write every trial's files and summary.csv here");
  cmd->add_flag("--quiet,-q", args->quiet, "no per-trial lines");
  cmd->callback([args, &exitCode]() {
    try {
      exitCode = runExperiments(*args);
    } catch (const std::exception& e) {
      fmt::print(stderr, "cbtl experiment: error: {}\n", e.what());
      exitCode = 1;
    }
  });
}

const cbtl::cli::RegisterCommand registerExperiment(15, addExperiment);

}  // namespace
