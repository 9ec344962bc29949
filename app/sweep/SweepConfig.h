// SweepConfig.h — a sweep: experiments (a program, approaches, seeds and `cbtl run` options, optionally a grid of
// option values), the figures to draw from their results, and how to run them on a SLURM cluster. One JSON file:
//
//   {
//     "name": "paper",                        // names the sbatch script and the job; default: the file's name
//     "out": "results",                       // the output folder (relative to where cbtl runs); --out overrides
//     "defaults": {"steps": 10000, "eval-every": 100, "eval-tasks": 10},
//     "experiments": [
//       {"name": "figure3", "program": "../../domains/cooking/cooking.cbtl",
//        "approaches": ["cbtl", "no-personalization"], "seeds": "0..9",
//        "options": {"replan": true, "unsatisfiable-stock": 0.5},
//        "grid": {"shift-every": [1000, 3000]}, "columns": [0, 500, 1000]}
//     ],
//     "plots": [
//       {"out": "figure3.png", "results": ["figure3"], "titles": ["Cooking"], "ymin": -1, "ymax": 1}
//     ],
//     "slurm": {"partition": "cpu", "cpus-per-task": 1, "mem": "2G", "time": "01:00:00", "array-limit": 50,
//               "trials-per-task": 1, "max-array-size": 1001, "sbatch": ["--account=mylab"]}
//   }
//
// Options are `cbtl run`'s long options without the dashes: a number or a string is the option's value, true a
// flag (false leaves it out). Experiment options override the defaults. The sweep itself sets --approach, --seed
// and --out, so an experiment may not. A grid makes one experiment per combination of its values, named
// "<name>/<option>=<value>,..." (its folder under out). A program path is relative to the config file's folder.
// Plots: "results" names experiments of the sweep (a grid's "<name>/<option>=<value>" too); the other fields are
// `cbtl plot`'s (kind, layout, titles, labels, approaches, metric, marks, at-step, title, xlabel, ylabel, ymin, ymax,
// width, height). Unknown keys anywhere are errors, so a typo is never ignored.
#pragma once

#include "app/plot/ResultsFigure.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::sweep {

// A config that cannot be read or is wrong: "<file>: <JSON pointer>: <what>".
struct SweepError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Option name (no dashes) -> value; a JSON object's keys come sorted by name.
using OptionList = std::vector<std::pair<std::string, nlohmann::json>>;

struct ExperimentSpec {
  std::string name;     // letters, digits, '.', '_' and '-'
  std::string program;  // absolute
  std::vector<std::string> approaches;
  std::vector<std::uint64_t> seeds;
  OptionList options;  // defaults first, then the experiment's (a later value of a name wins)
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> grid;
  std::vector<std::int64_t> columns;  // the checkpoints its table shows (`cbtl experiment --columns`); empty: default
  std::string where;                  // "/experiments/<i>", for messages
};

struct PlotSpec {
  std::string out;                   // relative to the sweep's output folder
  std::vector<std::string> results;  // experiment names
  plot::FigureRequest request;       // its results are filled in when the output folder is known
  std::string where;
};

struct SlurmSpec {
  std::string partition, time = "01:00:00", mem = "2G";
  int cpusPerTask = 1;
  int arrayLimit = 0;               // tasks running at once (sbatch --array=...%N); 0: no limit
  int trialsPerTask = 1;            // trials one array task runs
  int maxArraySize = 1001;          // the cluster's MaxArraySize: more tasks than this and tasks take more trials
  std::vector<std::string> sbatch;  // more #SBATCH lines, e.g. "--account=mylab"
};

struct SweepConfig {
  std::string path;  // the file, absolute
  std::string name;
  std::string out;
  std::vector<ExperimentSpec> experiments;
  std::vector<PlotSpec> plots;
  SlurmSpec slurm;
};

// Reads and checks `path` (JSON). Throws SweepError.
SweepConfig readSweepConfig(const std::string& path);

// "0..9", "3" or "1,4,7" (at most 10001 seeds; digits only, so "-1", "0-9" and "1.5" are refused); false for
// anything else. `cbtl experiment --seeds` and a sweep's "seeds" read the same syntax.
bool parseSeedList(const std::string& text, std::vector<std::uint64_t>& seeds);

}  // namespace cbtl::sweep
