// GraphPrinter.h — dumps of the ConstraintGraph: human text, JSON (the serialisation the runtime
// reads), and Graphviz DOT (variables as ellipses, constraints as boxes, one edge per incidence).
// All three are deterministic: same graph, same bytes.
#pragma once

#include "ir/ConstraintGraph.h"

#include <string>

namespace cbtl::ir {

std::string toText(const ConstraintGraph& g);
std::string toJson(const ConstraintGraph& g);
std::string toDot(const ConstraintGraph& g);
// An expression in source-like infix form, with variables by name.
std::string exprText(const Expr& e, const ConstraintGraph& g);

}  // namespace cbtl::ir
