// TypeChecker.h — the `check-types` pass.
//
// Gives every expression a type (Expr::type) and checks every declaration against its context:
// constraints are bool, costs are numbers, domains fit their variable types, constants and domain
// bounds do not depend on variables, calls match the extern signatures declared in the standard library
// (arity, named arguments, argument types with vec<N>/Conf<R> unification), samples write variables
// with values of the right type, skill instances pass variables of the skills' parameter types, and
// user functions are not recursive, clearances and allow statements give distances with a unit (m, cm, mm) that
// are not negative, and an allow's part, mode and target are what it takes. Reports E03xx, E05xx and E0601,
// E0602, E0604, E0605 (the world's names are checked by check-world).
//
// Expressions inside personalized generators (model arguments, labels) are typed here too; their
// meaning is checked by the `check-generators` pass.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"

#include <memory>
#include <vector>

namespace cbtl {

bool checkTypes(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, const GlobalSymbols& symbols,
                DiagnosticEngine& diags);

// The declared element type of a variable, constant or observation (its family element for families).
const Type* declaredType(const Decl& d);

// True if the expression (already typed) depends only on constants, enum members, items, literals and
// built-in constants; with `allowObservations`, observations are allowed too.
bool isConstantExpr(const Expr& e, bool allowObservations);

}  // namespace cbtl
