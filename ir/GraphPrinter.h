// GraphPrinter.h — dumps of the ConstraintGraph: human text, JSON (the serialisation the runtime
// reads), and Graphviz DOT (GraphDot.cpp: a cluster per task with its variables, hard constraints, samplers and the
// personalized constraints its generators would create; clearances apart).
// All three are deterministic: same graph, same bytes.
//
// The JSON is complete: ir/GraphJsonReader.h reads it back into the same graph (every field, the kind of
// every type included), so `cbtl` can run an emitted graph without the front end. Its top-level "format"
// tag and "version" say which revision of the layout a file has; the version grows whenever a field the
// reader needs is added or a field changes meaning (version 2 added the type kinds and the entries'
// "field_order"; version 3 the clearances and the allow actions).
#pragma once

#include "ir/ConstraintGraph.h"

#include <string>

namespace cbtl::ir {

inline constexpr const char* kGraphJsonFormat = "cbtl-constraint-graph";
inline constexpr int kGraphJsonVersion = 3;

std::string toText(const ConstraintGraph& g);
std::string toJson(const ConstraintGraph& g);
std::string toDot(const ConstraintGraph& g);
// An expression in source-like infix form, with variables by name.
std::string exprText(const Expr& e, const ConstraintGraph& g);

}  // namespace cbtl::ir
