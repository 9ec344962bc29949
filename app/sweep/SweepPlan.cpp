#include "app/sweep/SweepPlan.h"

#include <fmt/format.h>

#include <filesystem>

namespace cbtl::sweep {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// An option's value as a command-line argument: strings as they are, numbers as JSON writes them (10000, 0.5).
std::string argumentText(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

void appendOption(std::vector<std::string>& args, const std::string& name, const json& value) {
  if (value.is_boolean()) {
    if (value.get<bool>()) args.push_back("--" + name);
    return;
  }
  args.push_back("--" + name);
  args.push_back(argumentText(value));
}

// A folder-safe rendering of a grid value: anything but letters, digits, '.', '_' and '-' becomes '_'.
std::string folderText(const json& v) {
  std::string s = argumentText(v);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  return s;
}

// The options of one experiment with the grid combination `choice` (an index per grid option), the later value of a
// name winning: defaults, then the experiment's options, then the grid's.
std::vector<std::string> argumentsOf(const ExperimentSpec& e, const std::vector<std::size_t>& choice) {
  OptionList merged;
  const auto set = [&](const std::string& name, const json& value) {
    for (auto& [n, v] : merged)
      if (n == name) {
        v = value;
        return;
      }
    merged.emplace_back(name, value);
  };
  for (const auto& [n, v] : e.options) set(n, v);
  for (std::size_t g = 0; g < e.grid.size(); ++g) set(e.grid[g].first, e.grid[g].second[choice[g]]);
  std::vector<std::string> args;
  for (const auto& [n, v] : merged) appendOption(args, n, v);
  return args;
}

}  // namespace

SweepPlan planSweep(const SweepConfig& config, const std::string& out) {
  SweepPlan plan;
  plan.out = out;
  for (const ExperimentSpec& e : config.experiments) {
    std::vector<std::size_t> choice(e.grid.size(), 0);
    for (bool more = true; more;) {
      PlannedExperiment x;
      x.name = e.name;
      std::string variant;
      for (std::size_t g = 0; g < e.grid.size(); ++g)
        variant += (variant.empty() ? "" : ",") + e.grid[g].first + "=" + folderText(e.grid[g].second[choice[g]]);
      if (!variant.empty()) x.name += "/" + variant;
      x.program = e.program;
      x.approaches = e.approaches;
      x.seeds = e.seeds;
      x.arguments = argumentsOf(e, choice);
      x.columns = e.columns;
      x.dir = (fs::path(out) / x.name).string();
      x.where = e.where;
      for (const auto& approach : x.approaches)
        for (auto seed : x.seeds) {
          SweepTrial t;
          t.index = plan.trials.size();
          t.experiment = plan.experiments.size();
          t.approach = approach;
          t.seed = seed;
          t.dir = fmt::format("{}/{}/seed{}", x.dir, approach, seed);
          x.trials.push_back(t.index);
          plan.trials.push_back(std::move(t));
        }
      plan.experiments.push_back(std::move(x));
      // The next combination: the last grid option varies fastest.
      more = false;
      for (std::size_t g = e.grid.size(); g-- > 0;) {
        if (++choice[g] < e.grid[g].second.size()) {
          more = true;
          break;
        }
        choice[g] = 0;
      }
    }
  }
  for (const PlotSpec& p : config.plots)
    for (std::size_t i = 0; i < p.results.size(); ++i) {
      bool found = false;
      for (const auto& x : plan.experiments) found = found || x.name == p.results[i];
      if (!found) {
        std::string names;
        for (const auto& x : plan.experiments) names += (names.empty() ? "" : ", ") + x.name;
        throw SweepError(fmt::format("{}: {}/results/{}: no experiment '{}' in this sweep (it has: {})", config.path,
                                     p.where, i, p.results[i], names));
      }
    }
  return plan;
}

bool trialComplete(const SweepTrial& trial) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(trial.dir) / "complete.json", ec);
}

std::size_t trialsPerTask(const SweepConfig& config, std::size_t trialCount) {
  std::size_t per = static_cast<std::size_t>(std::max(1, config.slurm.trialsPerTask));
  const std::size_t maxTasks = static_cast<std::size_t>(std::max(1, config.slurm.maxArraySize));
  if ((trialCount + per - 1) / per > maxTasks) per = (trialCount + maxTasks - 1) / maxTasks;
  return per;
}

std::vector<std::size_t> trialsOfTask(const SweepConfig& config, const SweepPlan& plan, std::size_t task) {
  const std::size_t per = trialsPerTask(config, plan.trials.size());
  std::vector<std::size_t> out;
  for (std::size_t i = task * per; i < plan.trials.size() && i < (task + 1) * per; ++i) out.push_back(i);
  return out;
}

std::string slurmScript(const SweepConfig& config, const SweepPlan& plan, const std::string& cbtl) {
  const std::size_t per = trialsPerTask(config, plan.trials.size());
  const std::size_t tasks = (plan.trials.size() + per - 1) / per;
  const SlurmSpec& s = config.slurm;
  const auto quoted = [](const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  std::string script = "#!/bin/bash\n";
  script +=
      fmt::format("# Generated by `cbtl sweep {} --emit-slurm`: {} trials in {} array task{} ({} trial{} each).\n",
                  config.path, plan.trials.size(), tasks, tasks == 1 ? "" : "s", per, per == 1 ? "" : "s");
  script += "# Submit with sbatch; when every task has finished: cbtl sweep CONFIG --out OUT --collect\n";
  script += fmt::format("#SBATCH --job-name=cbtl-{}\n", config.name);
  script +=
      fmt::format("#SBATCH --array=0-{}{}\n", tasks - 1, s.arrayLimit > 0 ? fmt::format("%{}", s.arrayLimit) : "");
  script += fmt::format("#SBATCH --cpus-per-task={}\n", s.cpusPerTask);
  script += fmt::format("#SBATCH --mem={}\n", s.mem);
  script += fmt::format("#SBATCH --time={}\n", s.time);
  if (!s.partition.empty()) script += fmt::format("#SBATCH --partition={}\n", s.partition);
  script += fmt::format("#SBATCH --output={}/slurm/%A_%a.log\n", plan.out);
  for (const auto& line : s.sbatch) script += "#SBATCH " + line + "\n";
  script += "set -euo pipefail\n";
  script += fmt::format("exec {} sweep {} --out {} --index \"$SLURM_ARRAY_TASK_ID\" --jobs {} --quiet\n", quoted(cbtl),
                        quoted(config.path), quoted(plan.out), s.cpusPerTask);
  return script;
}

}  // namespace cbtl::sweep
