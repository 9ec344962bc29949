// TrialPool.h — the trials of `cbtl experiment` on several threads (`--jobs N`).
//
// A Program, its robot world and its simulators are used by one thread at a time, so each worker loads the
// program itself (compiling the .cbtl file again, or reading the emitted graph) and makes its own simulators and
// text backend. A trial's result depends only on its configuration (its seed, approach and options), so the
// results are those of a serial run, whatever order the trials finish in; they are returned in the order given.
// Run folders are per trial, so workers never write the same file. An external simulator is started per trial (its
// own process), so trials share nothing there either.
#pragma once

#include "runtime/approach/Experiment.h"
#include "tools/cbtl/RuntimeSupport.h"

#include <exception>
#include <functional>
#include <vector>

namespace cbtl::cli {

struct TrialOutcome {
  approach::ExperimentResult result;
  double seconds = 0;  // wall clock of the trial (a trial finished earlier: what its timing.json recorded, or 0)
  bool finishedEarlier = false;  // read back from a complete run folder by --resume
  std::exception_ptr error;      // what the trial threw, if it did (rethrown by the caller in trial order)
};

// Runs `trials` on `jobs` threads (1: in the calling thread, with `program`). `onDone(i, outcome)` is called once
// per trial as it finishes, one call at a time. The text backend of each worker is made from `text` (each
// counts its own faults); trials' own textBackend fields are replaced.
std::vector<TrialOutcome> runTrials(const app::LoadedProgram& program, const std::string& file,
                                    const std::string& stdlibDir, const TextBackendArgs& text,
                                    const ExternalSimulatorArgs& external,
                                    std::vector<approach::ExperimentConfig> trials, int jobs,
                                    const std::function<void(std::size_t, const TrialOutcome&)>& onDone);

}  // namespace cbtl::cli
