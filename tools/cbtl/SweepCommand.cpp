// `cbtl sweep CONFIG`: a grid of experiments (app/sweep/SweepConfig.h) run as independent trials.
//   cbtl sweep CONFIG [--jobs N]      runs every unfinished trial on N threads, with a live count and an ETA, then
//                                     collects (summary.csv per experiment, the tables, the config's figures)
//   cbtl sweep CONFIG --index I       runs SLURM array task I's trials only (the sbatch script calls this)
//   cbtl sweep CONFIG --collect       collects what has finished, running nothing
//   cbtl sweep CONFIG --emit-slurm    writes OUT/<name>.sbatch, a job array over the trials
//   cbtl sweep CONFIG --list          lists the trials: index, state, experiment, approach, seed, folder
// An interrupted sweep continues where it stopped: run the same command again. Exit codes: 0 ok, 1 bad config,
// failed or unfinished trials, 2 usage, 3 an experiment's requests failed above its --max-failure-rate (an option
// like any other: "max-failure-rate": 1 in its options accepts any), 70 internal error.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/SweepRunner.h"
#include "tools/cbtl/TrialProgress.h"

#include "app/sweep/SweepConfig.h"
#include "app/sweep/SweepPlan.h"
#include "runtime/approach/RunDirectory.h"

#include <fmt/core.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;

struct SweepArgs {
  std::string config, out;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::int64_t index = -1;
  bool collect = false, emitSlurm = false, list = false, quiet = false;
};

// The live display: on a terminal one line rewritten in place, elsewhere a line per finished trial.
class Progress {
 public:
  Progress(std::size_t total, std::size_t alreadyDone, bool quiet)
      : line_(total, alreadyDone), quiet_(quiet), terminal_(::isatty(2) != 0) {
    if (!quiet_ && alreadyDone > 0)
      fmt::print(stderr, "cbtl sweep: {} of {} trials already finished; running the other {}\n", alreadyDone, total,
                 total - alreadyDone);
  }

  void finished(const cbtl::sweep::SweepPlan& plan, const cbtl::cli::TrialEvent& e) {
    const auto& t = plan.trials[e.trial];
    const std::string what = fmt::format("{} {} seed {}", plan.experiments[t.experiment].name, t.approach, t.seed);
    const std::string line = line_.finished(what, e.seconds);
    if (e.failed) fmt::print(stderr, "{}cbtl sweep: {} failed: {}\n", terminal_ ? "\r\x1b[K" : "", what, e.error);
    if (quiet_) return;
    const bool last = line_.done() == line_.total();
    if (terminal_)
      fmt::print(stderr, "\r\x1b[K{}{}", line, last ? "\n" : "");
    else
      fmt::print(stderr, "{}\n", line);
  }

 private:
  cbtl::cli::TrialProgress line_;
  bool quiet_, terminal_;
};

int emitSlurm(const cbtl::sweep::SweepConfig& config, const cbtl::sweep::SweepPlan& plan) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  fs::create_directories(fs::path(plan.out) / "slurm");
  const std::string path = (fs::path(plan.out) / (config.name + ".sbatch")).string();
  cbtl::approach::writeFileAtomic(path,
                                  cbtl::sweep::slurmScript(config, plan, ec ? std::string("cbtl") : self.string()));
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add, ec);
  const std::size_t per = cbtl::sweep::trialsPerTask(config, plan.trials.size());
  fmt::print("wrote {}: {} trials in {} array tasks of {} trial{}\n", path, plan.trials.size(),
             (plan.trials.size() + per - 1) / per, per, per == 1 ? "" : "s");
  fmt::print("submit it with:   sbatch {}\nthen collect with: cbtl sweep {} --out {} --collect\n", path, config.path,
             plan.out);
  return 0;
}

int listTrials(const cbtl::sweep::SweepPlan& plan) {
  for (const auto& t : plan.trials) {
    const bool done = cbtl::sweep::trialComplete(t);
    const bool started = !done && !cbtl::approach::runFilesIn(t.dir).empty();
    fmt::print("{:>5}  {:<8} {} {} seed {}  {}\n", t.index,
               done      ? "done"
               : started ? "partial"
                         : "todo",
               plan.experiments[t.experiment].name, t.approach, t.seed, t.dir);
  }
  return 0;
}

int runSweep(const SweepArgs& a) {
  using namespace cbtl;
  sweep::SweepConfig config;
  sweep::SweepPlan plan;
  try {
    config = sweep::readSweepConfig(a.config);
    plan = sweep::planSweep(config, fs::absolute(a.out.empty() ? config.out : a.out).lexically_normal().string());
  } catch (const sweep::SweepError& e) {
    fmt::print(stderr, "cbtl sweep: error: {}\n", e.what());
    return 1;
  }
  if (a.list) return listTrials(plan);
  if (a.emitSlurm) return emitSlurm(config, plan);
  std::vector<cli::PreparedExperiment> prepared;
  try {
    prepared = cli::prepareSweep(config, plan);
  } catch (const sweep::SweepError& e) {
    fmt::print(stderr, "cbtl sweep: error: {}\n", e.what());
    return 1;
  }
  if (a.collect) return cli::collectSweep(config, plan, prepared);
  std::vector<std::size_t> indices;
  if (a.index >= 0) {
    indices = sweep::trialsOfTask(config, plan, static_cast<std::size_t>(a.index));
    if (indices.empty()) {
      const std::size_t per = sweep::trialsPerTask(config, plan.trials.size());
      fmt::print(stderr, "cbtl sweep: error: --index {}: the sweep has {} array tasks (0..{})\n", a.index,
                 (plan.trials.size() + per - 1) / per, (plan.trials.size() + per - 1) / per - 1);
      return 2;
    }
  } else {
    for (const auto& t : plan.trials) indices.push_back(t.index);
  }
  std::vector<std::size_t> todo;
  for (std::size_t i : indices)
    if (!sweep::trialComplete(plan.trials[i])) todo.push_back(i);
  Progress progress(indices.size(), indices.size() - todo.size(), a.quiet);
  std::map<std::size_t, double> seconds;
  const std::size_t failed = cli::runSweepTrials(plan, prepared, todo, a.jobs, [&](const cli::TrialEvent& e) {
    progress.finished(plan, e);
    seconds[e.trial] = e.seconds;
  });
  if (failed > 0) {
    fmt::print(stderr, "cbtl sweep: {} trial{} failed (above); run the sweep again to retry them\n", failed,
               failed == 1 ? "" : "s");
    return 1;
  }
  if (a.index >= 0) return 0;  // a SLURM task: `--collect` merges once every task has finished
  return cli::collectSweep(config, plan, prepared, seconds);
}

void addSweep(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "run a grid of experiments (a JSON config) in parallel or on a SLURM cluster, then tables and figures");
  cmd->add_option("config", args->config, "the sweep's JSON file (docs/sweeps.md)")->required();
  cmd->add_option("--out", args->out, "output folder (default: the config's \"out\")");
  cmd->add_option("--jobs,-j", args->jobs, "trials run in parallel (results equal a serial run's)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  auto* index = cmd->add_option("--index", args->index, "run only this SLURM array task's trials (0-based)")
                    ->check(CLI::NonNegativeNumber);
  auto* collect = cmd->add_flag("--collect", args->collect, "run nothing: summarize finished trials, draw the figures");
  auto* slurm =
      cmd->add_flag("--emit-slurm", args->emitSlurm, "write OUT/<name>.sbatch, a SLURM job array of the trials");
  auto* list = cmd->add_flag("--list", args->list, "list the trials and whether each has finished");
  index->excludes(collect)->excludes(slurm)->excludes(list);
  collect->excludes(slurm)->excludes(list);
  slurm->excludes(list);
  cmd->add_flag("--quiet,-q", args->quiet, "no progress lines");
  cmd->callback([args, &exitCode]() { cbtl::cli::runCommand("sweep", exitCode, [&] { return runSweep(*args); }); });
}

const cbtl::cli::RegisterCommand registerSweep(16, addSweep);

}  // namespace
