// Lowering.h — the `lower` pass: checked AST -> ConstraintGraph.
//
// Instantiates every task (top-level declarations, the task's own, and each skill instance with its
// variables renamed "<instance>.<var>"), expands variable families into members, unrolls top-level
// `forall` over compile-time finite sets into one constraint per binding (a `where` that cannot be
// decided at compile time becomes an implication; one with more than 10000 instances keeps its
// quantifier), and records each constraint's hyperedge. Also reports W0401 (a generator pattern that
// matches no variable of any task), W0501 (unused skill), W0201 and W0502 (lower/UsageWarnings.h), and
// E0317 when families, unrolling and skill instances would make the graph too large.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "ir/ConstraintGraph.h"

#include <memory>
#include <vector>

namespace cbtl {

bool lowerToGraph(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                  const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& graph);

}  // namespace cbtl
