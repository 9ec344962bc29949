// ActionPlan.h — a task's skills turned into the sequence of action calls that executes a solution.
//
// Each skill instance's `do` block is compiled once; given a solution it unrolls (loops over enums and
// integer ranges, conditionals) into concrete calls whose arguments are values at the simulator boundary.
// The calls are computed once per solution: the policy is open loop, as in the paper.
//
// Skill instance k of the task is the plan's *stage* k (solver/StagedPlan.h): TaskActions also knows which
// stage each constraint, sampler and variable belongs to (task-level ones: stage 0) and which variables the
// actions of each stage read, so the runtime can evaluate a stage in the state the earlier ones leave
// (runtime/approach/PlanExecution.h).
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::approach {

struct CompiledAction {
  ir::ActionKind kind = ir::ActionKind::Block;
  std::string name;
  std::vector<std::uint32_t> args;  // a call's arguments; an allow's target (when it is not a declared clearance)
  std::vector<rt::ValueType> argTypes;
  sim::ClearanceException exception;  // allow: the exception, with the clearance's bodies when it names one
  std::uint32_t binderSlot = 0;
  std::uint32_t memberCount = 0;        // for over an enum / item set
  std::optional<std::uint32_t> lo, hi;  // for over an integer range
  std::optional<std::uint32_t> condition;
  std::vector<CompiledAction> body, elseBody;
};

class TaskActions {
 public:
  // Throws rt::RuntimeError for an action the runtime cannot execute.
  TaskActions(rt::Program& program, const ir::Task& task);

  // The calls for a solution, in order, every stage evaluated in the same world. Loops are capped at 100,000
  // calls in total. Each call carries the exceptions of the `allow` blocks around it, outermost first.
  std::vector<sim::ActionCall> unroll(const rt::Program& program, const std::vector<double>& solution,
                                      const std::vector<double>& observation) const;
  // Appends the calls of stage `stage` for the assignment `x` and observation `obs` (laid out as the program
  // says) to `out`, within the same cap.
  void unrollStage(const rt::Program& program, std::size_t stage, const double* x, const double* obs,
                   std::vector<sim::ActionCall>& out) const;

  std::size_t stageCount() const { return stages_.size(); }
  // Variables read by the actions of stages 0..stage-1, sorted; and by every action.
  const std::vector<ir::VarId>& readsBefore(std::size_t stage) const { return readsBefore_.at(stage); }
  const std::vector<ir::VarId>& reads() const { return readsBefore_.back(); }
  // The stage of a graph constraint, a program sampler and a variable of the task (0 when task-level).
  std::uint32_t constraintStage(std::uint32_t constraint) const;
  std::uint32_t samplerStage(std::uint32_t sampler) const;
  std::uint32_t variableStage(ir::VarId v) const;
  // Every action the task's skills call (sorted, unique).
  const std::vector<std::string>& actionNames() const { return actionNames_; }

 private:
  std::vector<std::vector<CompiledAction>> stages_;
  std::uint32_t frameWidth_ = 0;
  std::vector<std::vector<ir::VarId>> readsBefore_;  // stageCount() + 1 rows; the last: every action's reads
  std::map<std::uint32_t, std::uint32_t> constraintStage_, samplerStage_, variableStage_;
  std::vector<std::string> actionNames_;
};

}  // namespace cbtl::approach
