// GeneratorMatch.h — which variables a personalized constraint generator's parameters can bind: those of the
// parameter's type whose name its initiation pattern (glob or regex; none: any name) matches. Captures are not
// correlated across parameters here, so this is the set a generator's constraints can read, not its tuples (the
// runtime's instantiation is exact). For the compiler's usage warnings and the DOT picture of the graph.
#pragma once

#include "ir/ConstraintGraph.h"

#include <set>
#include <vector>

namespace cbtl::ir {

// The variables among `candidates` some parameter of `gen` can match.
std::set<VarId> variablesMatchedBy(const ConstraintGraph& graph, const Generator& gen,
                                   const std::vector<VarId>& candidates);

}  // namespace cbtl::ir
