// NameResolver.h — the `resolve-names` pass.
//
// Builds the global symbol table from every module of the translation unit, resolves every type as
// written to a semantic Type, and every name in expressions, samples, actions, skill instances and
// learning rules to its declaration (Expr::ref and friends). Scopes, innermost first: quantifier and
// learn binders, function / generator / skill parameters, skill or task variables, then the global
// namespace, then unambiguous enum members, then built-ins (pi, uniform, box). An `allow` target that is a bare
// name naming a declared clearance is that clearance (AllowClause::clearance), whatever else is in scope; clearance
// names are no values anywhere else. Reports E02xx and the type-argument errors E0309; suggests the closest name for
// typos.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"

#include <memory>
#include <vector>

namespace cbtl {

// Resolves all modules (root first, imports after). Returns false if errors were reported.
bool resolveNames(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, GlobalSymbols& symbols,
                  DiagnosticEngine& diags);

}  // namespace cbtl
