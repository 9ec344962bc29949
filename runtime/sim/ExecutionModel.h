// ExecutionModel.h — what the runtime asks of a world model so that it accepts only plans the world can carry
// out: the state each skill of a plan starts in (state progression), and a dry run of the whole plan with
// every check the executor applies.
//
// The robot world implements it (robot/bind/WorldHost.h) with the same executor the domain's simulator acts
// with; the runtime sees only this interface (the solver's staged evaluation, runtime/approach/PlanExecution.h).
//
// Both functions start from the *observed* state, the one the runtime last copied from the simulator before the
// CSP was made, and are pure: the same state and calls give the same verdict. Neither leaves a trace in the
// world the simulator acts on.
#pragma once

#include "runtime/sim/DomainSimulator.h"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace cbtl::sim {

struct PlanVerdict {
  bool executes = true;
  std::size_t failedCall = 0;  // when !executes: index of the first call that fails
  std::string action;          // its name
  std::string status;          // why, in a few words ("no collision-free path", "placement blocked", ...)
  std::string detail;          // and in full ("invalid goal", "book_3 would touch book_5 (too close)", ...)
};

class ExecutionModel {
 public:
  virtual ~ExecutionModel() = default;

  // Makes the world the program's built-ins read the observed state with the end effects of `prefix` applied
  // (motions teleport; no path is checked): the state the next skill starts in. An empty prefix restores the
  // observed state. When an effect is undefined (placing while holding nothing, an unknown body, no IK for a
  // tool move) the verdict names that call and the built-ins read the observed state.
  virtual PlanVerdict enterStage(std::span<const ActionCall> prefix) = 0;

  // Runs `calls` from the observed state with every check the executor applies (planned motions, collisions,
  // placements, sweeps) and says whether all of them succeed. Each motion may use at most `motionIterations`
  // planner iterations (0: only the straight segment); a motion that needs more fails the dry run. The
  // built-ins' state is left as it was.
  virtual PlanVerdict dryRun(std::span<const ActionCall> calls, int motionIterations) = 0;

  // Whether the model can execute an action of this name (a plan that calls another cannot be dry-run).
  virtual bool models(std::string_view action) const = 0;
};

}  // namespace cbtl::sim
