// SweepPlan.h — a sweep expanded into independent trials (one approach, one seed, one combination of options of
// one program), each with its own run folder, and grouped back into the experiments they summarize.
//
// Order (a trial's index, which SLURM array tasks use): experiments as the config lists them; within one, the grid's
// combinations (the first grid option varies slowest), then approaches, then seeds, all in the config's order.
// Folders: OUT/<experiment>[/<option>=<value>,...]/<approach>/seed<S>, as `cbtl experiment --out
// OUT/<experiment>` lays them out, so every experiment folder is also an experiment `cbtl plot` and `cbtl
// experiment --resume` understand. A finished trial holds complete.json (its completion marker).
#pragma once

#include "app/sweep/SweepConfig.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::sweep {

struct SweepTrial {
  std::size_t index = 0;
  std::size_t experiment = 0;  // into SweepPlan::experiments
  std::string approach;
  std::uint64_t seed = 0;
  std::string dir;  // the trial's run folder
};

struct PlannedExperiment {
  std::string name;  // "<experiment>" or "<experiment>/<option>=<value>,..."
  std::string program;
  std::vector<std::string> approaches;
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> arguments;  // the `cbtl run` options of its trials, e.g. {"--steps", "10000", "--replan"}
  std::vector<std::int64_t> columns;   // the checkpoints its table shows (empty: the default)
  std::string dir;                     // OUT/<name>
  std::string where;                   // the config's JSON pointer
  std::vector<std::size_t> trials;     // indices into SweepPlan::trials
};

struct SweepPlan {
  std::string out;
  std::vector<PlannedExperiment> experiments;
  std::vector<SweepTrial> trials;
};

// Expands `config` into trials under `out`. Throws SweepError for a plot naming no experiment of the sweep.
SweepPlan planSweep(const SweepConfig& config, const std::string& out);

// Whether a trial has finished: its folder holds complete.json.
bool trialComplete(const SweepTrial& trial);

// SLURM: how many trials one array task runs (the config's trials-per-task, raised so that the array fits the
// cluster's max-array-size), and the trials of array task `task` (empty past the last).
std::size_t trialsPerTask(const SweepConfig& config, std::size_t trialCount);
std::vector<std::size_t> trialsOfTask(const SweepConfig& config, const SweepPlan& plan, std::size_t task);

// The sbatch script that runs the sweep as a job array: each task runs `<cbtl> sweep <config> --out <out> --index
// $SLURM_ARRAY_TASK_ID`, with the config's resources; logs go to OUT/slurm/<job>_<task>.log. `cbtl`, the config and
// `out` must be absolute paths the cluster's nodes see.
std::string slurmScript(const SweepConfig& config, const SweepPlan& plan, const std::string& cbtl);

}  // namespace cbtl::sweep
