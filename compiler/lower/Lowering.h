// Lowering.h — the `lower` pass: checked AST -> ConstraintGraph.
//
// Instantiates every task (top-level declarations, the task's own, and each skill instance with its
// variables renamed "<instance>.<var>"), expands variable families into members, unrolls top-level
// `forall` over compile-time finite sets into one constraint per binding (a `where` that cannot be
// decided at compile time becomes an implication), and records each constraint's hyperedge. Also
// reports W0401 (a generator pattern that matches no variable of any task) and W0501 (unused skill).
#pragma once

#include "ast/Ast.h"
#include "diag/DiagnosticEngine.h"
#include "ir/ConstraintGraph.h"
#include "sema/Symbols.h"

#include <memory>
#include <vector>

namespace cbtl {

bool lowerToGraph(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                  const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& graph);

}  // namespace cbtl
