// ExperimentReport.h — what `cbtl experiment` and `cbtl sweep` report about a finished experiment (approaches x
// seeds of one program and options): summary.csv (mean and standard error over seeds of the evaluation satisfaction
// at every checkpoint, with task success and preferences met), preferences.csv (each judged preference's met rate)
// and the tables on stdout.
#pragma once

#include "runtime/approach/Approach.h"
#include "runtime/approach/Experiment.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::cli {

// One finished trial.
struct TrialRecord {
  approach::ApproachKind kind;
  std::uint64_t seed = 0;
  const approach::ExperimentResult* result = nullptr;
  double seconds = 0;  // wall clock of the trial (0 when it was read back, not run)
};

// The checkpoints the table shows: `steps` when `given`, else 0, 5 %, 10 %, 25 %, 50 % and 100 % of
// trainingSteps snapped to evalEvery.
struct ReportColumns {
  std::vector<std::int64_t> steps;
  bool given = false;
  std::int64_t trainingSteps = 0, evalEvery = 1;
  int evalTasks = 0;
};

// The run folder of one trial of an experiment written to `out`: OUT/<approach>/seed<S>.
std::string trialFolder(const std::string& out, approach::ApproachKind kind, std::uint64_t seed);

// Each approach's training and evaluation over every seed, against `maxRate` (app/RunFailures.h): prints the
// warning naming `command` and `file` on stderr and returns 3 when a phase failed too often, else 0.
int checkFailureRates(const std::string& command, const std::string& file,
                      const std::vector<approach::ApproachKind>& kinds, const std::vector<TrialRecord>& trials,
                      double maxRate);

// Writes summary.csv and preferences.csv to `out` (atomically; nothing when `out` is empty) and prints the tables
// for `kinds` in that order. Returns 0, or 70 when a trial refused an accepted solution at its re-check (a runtime
// bug, said on stderr naming `command`).
int reportExperiment(const std::string& command, const std::vector<approach::ApproachKind>& kinds,
                     std::size_t seedCount, const std::vector<TrialRecord>& trials, const ReportColumns& columns,
                     const std::string& out);

}  // namespace cbtl::cli
