// SummaryTable.h — an experiment's results as `cbtl experiment` and `cbtl sweep` write them (summary.csv:
// approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean), read back for plotting.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::plot {

// A results file that cannot be read or is not a summary; the message names the file and, where it applies, the
// line (`summary.csv:7: ...`).
struct ResultsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  std::int64_t step = 0;  // training steps
  int seeds = 0;
  double evalMean = 0, evalSe = 0;  // evaluation satisfaction, mean and standard error over seeds
  double taskSuccess = 0, preferencesMet = 0;
};

struct SummaryTable {
  std::string path;  // the summary.csv read
  // Approach name -> its checkpoints by increasing step, approaches in the order the file first names them.
  std::vector<std::string> approaches;
  std::map<std::string, std::vector<Checkpoint>> byApproach;
};

// Reads `path`: a summary.csv, a folder that holds one, or a single run's folder (`cbtl run --out DIR`: its
// eval.csv, one seed, no standard error, named by its config.json's approach). Throws ResultsError.
SummaryTable readSummary(const std::string& path);

}  // namespace cbtl::plot
