// Validator.h — checks a ConstraintGraph independently of the front end that produced it.
//
// Every id is in range; each constraint's hyperedge is exactly the set of variables its expression reads;
// every task's constraints, samplers and costs read only the task's variables; variable names are unique
// within a task; samplers write at least one variable; generator patterns compile; spans are present;
// clearances have unique names, a finite distance >= 0 and at least one body; an allow action has exactly one of
// a clearance (a declared one) and a target, a finite separation and at least one action in its body.
// Returns the list of problems (empty if valid). A problem is a bug in whatever produced the graph.
#pragma once

#include "ir/ConstraintGraph.h"

#include <string>
#include <vector>

namespace cbtl::ir {

std::vector<std::string> validate(const ConstraintGraph& g);

}  // namespace cbtl::ir
