// RunFailures.h — whether a run or an experiment failed too often to be an ordinary result, and why, as far as the
// counts can tell.
//
// A request fails when it is not solved within the solver's budget or its solved plan fails in execution (a failed
// action: no IK, no path, a refused call). `cbtl run` and `cbtl experiment` compare each phase's failure rate
// (training, evaluation) with `--max-failure-rate` (default 0.10): above it they say so on stderr, naming the causes
// the counts show, and exit 3 instead of 0, so that a script cannot mistake a stuck run for a result. A caller that
// expects failures (an experiment about unsatisfiable requests) passes a higher rate; 1 accepts everything.
#pragma once

#include "runtime/approach/Experiment.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::app {

inline constexpr double kDefaultMaxFailureRate = 0.10;

// One phase's failures, from its competence counts (approach::Competence).
struct PhaseFailures {
  std::string phase;  // "training" or "evaluation"
  std::int64_t requests = 0;
  std::int64_t unsolved = 0;         // not solved within budget
  std::int64_t failedExecution = 0;  // solved, then an action failed
  std::int64_t caregiverResets = 0;  // a person put a stuck robot back (training only)
  std::int64_t failures() const { return unsolved + failedExecution; }
  double rate() const { return requests > 0 ? static_cast<double>(failures()) / static_cast<double>(requests) : 0.0; }
};

PhaseFailures phaseFailures(const std::string& phase, const approach::Competence& c);

// The evaluation phase's failures that say something is broken: plans that failed in execution. Its unsolved
// requests are left out: evaluation solves with what was learned, and preferences no plan can meet (the paper's
// Table 1, a shifted user in Figure 5) are an outcome the experiment measures, not a stuck run. Training requests
// (CBTL and Free Explore plan them with the hard constraints only) count in full.
PhaseFailures evaluationFailures(const std::string& phase, const approach::Competence& c);

// The phases whose failure rate is above `maxRate` (in [0, 1]), in the order given.
std::vector<PhaseFailures> phasesAbove(const std::vector<PhaseFailures>& phases, double maxRate);

// The warning for the phases above the rate: one line per phase with its counts, then what to do about each cause
// the counts show (unsolved: `cbtl solve --explain` and the simulator's training world; failed execution: the
// motions), then how to accept it. `file` is the program the command ran (quoted in the advice). Empty when
// `above` is.
std::string failureWarning(const std::string& command, const std::string& file, const std::vector<PhaseFailures>& above,
                           double maxRate);

}  // namespace cbtl::app
