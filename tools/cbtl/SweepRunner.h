// SweepRunner.h — runs a sweep's trials (app/sweep/SweepPlan.h) on threads and collects finished experiments into
// their tables and figures.
//
// Every trial is a `cbtl run` of its experiment's program and options with its approach and seed, written to its
// own folder with --resume semantics: a finished trial (complete.json) is never run again, an interrupted one
// continues from its last checkpoint, so a sweep stopped at any point and started again ends with the files of an
// uninterrupted one. Trials depend only on their own configuration, so the files are the same whatever the number
// of threads or the order in which trials finish. Each thread loads the programs itself (TrialPool.h says why).
#pragma once

#include "app/sweep/SweepPlan.h"
#include "runtime/approach/Experiment.h"
#include "tools/cbtl/RuntimeSupport.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cbtl::cli {

// An experiment's options, parsed and checked as `cbtl run` checks them.
struct PreparedExperiment {
  TrialArgs args;
  approach::ExperimentConfig base;            // everything but approach, seed, outDir and the solver's budgets
  std::vector<approach::ApproachKind> kinds;  // the experiment's approaches, in order
};

// Parses every experiment's options and approaches and loads every program once (printing its diagnostics).
// Throws sweep::SweepError naming the experiment and what is wrong.
std::vector<PreparedExperiment> prepareSweep(const sweep::SweepConfig& config, const sweep::SweepPlan& plan);

struct TrialEvent {
  std::size_t trial = 0;
  bool failed = false;
  std::string error;  // when failed
  double seconds = 0;
};

// Runs the trials `indices` of `plan` on `jobs` threads; `onDone` is called once per trial, one call at a time.
// Returns the number of trials that failed (each reported through onDone).
std::size_t runSweepTrials(const sweep::SweepPlan& plan, const std::vector<PreparedExperiment>& prepared,
                           const std::vector<std::size_t>& indices, int jobs,
                           const std::function<void(const TrialEvent&)>& onDone);

// For every experiment whose trials have all finished: summary.csv and preferences.csv in its folder and its tables
// on stdout; then every plot whose experiments are all collected. Experiments with unfinished trials are named on
// stderr. `seconds`: the wall clock of the trials this process ran, by index (the tables' s/trial averages those;
// "-" for an experiment none of whose trials ran here). Returns 0 when everything was collected, 1 when something
// was not finished or a figure failed, 3 when an experiment's requests failed above its --max-failure-rate
// (checkFailureRates), 70 as reportExperiment does.
int collectSweep(const sweep::SweepConfig& config, const sweep::SweepPlan& plan,
                 const std::vector<PreparedExperiment>& prepared, const std::map<std::size_t, double>& seconds = {});

}  // namespace cbtl::cli
