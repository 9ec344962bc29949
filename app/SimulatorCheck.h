// SimulatorCheck.h — `cbtl simulator check`'s exercise of a simulator: every request of the protocol that a run
// makes, with plans the solver produced, so that a simulator which "fits" also survives a run's first minutes.
//
// After the manifest and the first observation (checked by the caller when the simulator starts), the exercise:
//   1. plans the task the world asks for (hard constraints only, the domain's budgets) and acts every call of the
//      plan, observing the world before each plan; an unsolved request lets one step pass with `idle`;
//   2. goes on, up to `maxRequests` plans, until every declared action has been acted and some step said `done`;
//   3. lets one step pass with `idle` (once more if step 1 never did);
//   4. makes an evaluation twin, resets and observes it, and acts the first call of a plan in it, then observes the
//      training world again (a twin's requests must not change it).
// The first exception (an answer that breaks the protocol: noise on stdout, an error answer, a crash, a timeout;
// or an action the simulator does not know) stops the exercise and is reported with what was being done.
// Nothing here is random beyond the seed: the same simulator and seed give the same report.
#pragma once

#include "app/LoadedProgram.h"
#include "runtime/sim/DomainSimulator.h"
#include "runtime/solver/Solver.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cbtl::app {

struct SimulatorCheckReport {
  std::vector<std::string> log;            // one line per request made, in order ("act brew(...): step, done")
  std::map<std::string, int> actsByName;   // calls acted, by action
  std::vector<std::string> notExercised;   // declared actions no plan used
  int plansSolved = 0, plansUnsolved = 0;  // requests planned
  bool sawDone = false, idled = false, twinChecked = false;
  std::string violation;  // the first request that broke the protocol, with the simulator's message; empty: none
  bool ok() const { return violation.empty(); }
};

// `actions`: the extern actions the program's tasks call (sim::ProtocolSchema::actions), the ones to exercise.
SimulatorCheckReport exerciseSimulator(const LoadedProgram& lp, sim::DomainSimulator& world,
                                       const std::vector<std::string>& actions, std::uint64_t seed,
                                       const solver::SolverOptions& options, int maxRequests = 8);

}  // namespace cbtl::app
