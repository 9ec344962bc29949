// ReadSet.h — the variables an expression reads, as the runtime evaluates it.
//
// The runtime inlines every non-extern function at its call sites, so an expression reads what its own
// variable references and family indexings name plus, transitively, what the bodies of the functions it calls
// read (`fn chosen(i: int) -> bool = flag[i]` makes `chosen(idx)` read idx and every member of flag). A read
// set that missed those would let the solver's cache keep a stale constraint result. Recursion between
// functions is rejected by the compiler; the walk guards against it anyway.
#pragma once

#include "ir/ConstraintGraph.h"

#include <set>

namespace cbtl::ir {

// Adds to `out` every variable `e` reads, following calls into the bodies of `graph`'s functions.
void collectReadVars(const ConstraintGraph& graph, const Expr& e, std::set<VarId>& out);

}  // namespace cbtl::ir
