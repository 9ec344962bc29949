// ActionPlan.h — a task's skills turned into the sequence of action calls that executes a solution.
//
// Each skill instance's `do` block is compiled once; given a solution it unrolls (loops over enums and
// integer ranges, conditionals) into concrete calls whose arguments are values at the simulator boundary.
// The calls are computed once per solution: the policy is open loop, as in the paper.
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <optional>
#include <vector>

namespace cbtl::approach {

struct CompiledAction {
  ir::ActionKind kind = ir::ActionKind::Block;
  std::string name;
  std::vector<std::uint32_t> args;
  std::vector<rt::ValueType> argTypes;
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

  // The calls for a solution, in order. Loops are capped at 100,000 calls in total.
  std::vector<sim::ActionCall> unroll(const rt::Program& program, const std::vector<double>& solution,
                                      const std::vector<double>& observation) const;

 private:
  std::vector<CompiledAction> actions_;
  std::uint32_t frameWidth_ = 0;
};

}  // namespace cbtl::approach
