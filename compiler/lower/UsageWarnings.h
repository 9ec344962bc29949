// UsageWarnings.h — warnings about declared variables that the constraint graph does not use (W0201) or
// for which the solver has no way to produce values (W0502) or never changes the value (W0503).
//
// Runs at the end of lowering, on the finished graph: "used" means read by a constraint, a sampler's
// arguments, a cost, an action of a skill instance (all tasks together), or matched by a personalized
// constraint generator's pattern (its constraints read the variable); "has a way to produce values"
// means written by a sampler; without one a variable keeps its initial value, or its starting value when it is
// declared with a bounded or finite domain (bool, enums, items, Conf<R> and every variable with `in ...`). Each
// declaration is reported once, however many members (families) or instances (skills run by several tasks) it has:
// W0201 when none of them is used, W0502 when a used one is unbounded, unsampled and without an initial value, W0503
// when a used one is unsampled but has an initial value or a bounded domain: only samplers move variables (the solver
// never draws from a declared domain by itself), so it keeps its starting value in every candidate.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "ir/ConstraintGraph.h"

#include <vector>

namespace cbtl {

// `declOf[id]` is the declaration of graph variable `id` (same size as graph.variables).
void reportUsageWarnings(const ir::ConstraintGraph& graph, const std::vector<const VarDecl*>& declOf,
                         DiagnosticEngine& diags);

}  // namespace cbtl
