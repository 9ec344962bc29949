// The `check-types` entry point and the declaration dispatch; the other concerns of
// the checker are implemented in the TypeChecker*.cpp files listed in TypeCheckerInternal.h.
#include "compiler/sema/TypeChecker.h"

#include "compiler/sema/TypeCheckerInternal.h"

#include <fmt/format.h>

namespace cbtl {

const Type* declaredType(const Decl& d) {
  switch (d.kind) {
    case DeclKind::Var:
      return static_cast<const VarDecl&>(d).type.resolved;
    case DeclKind::Observe:
      return static_cast<const ObserveDecl&>(d).type.resolved;
    case DeclKind::Const:
      return static_cast<const ConstDecl&>(d).valueType;
    default:
      return nullptr;
  }
}

bool isConstantExpr(const Expr& e, bool allowObservations) {
  if (e.kind == ExprKind::Name || ((e.kind == ExprKind::Member) && e.ref.kind != RefKind::Unresolved)) {
    switch (e.ref.kind) {
      case RefKind::Const:
      case RefKind::EnumType:
      case RefKind::EnumMember:
      case RefKind::ItemSet:
      case RefKind::ItemEntry:
      case RefKind::Builtin:
      case RefKind::Binder:
        return true;
      case RefKind::Observation:
        return allowObservations;
      case RefKind::Unresolved:
        return e.kind == ExprKind::Member ? isConstantExpr(*e.operands[0], allowObservations) : true;
      default:
        return false;
    }
  }
  if (e.kind == ExprKind::Call && e.ref.kind == RefKind::Function) {
    // Calls of pure functions on constants are constant.
    for (const auto& a : e.args) {
      if (a.value && !isConstantExpr(*a.value, allowObservations)) return false;
    }
    return true;
  }
  for (const auto& op : e.operands) {
    if (op && !isConstantExpr(*op, allowObservations)) return false;
  }
  for (const auto& a : e.args) {
    if (a.value && !isConstantExpr(*a.value, allowObservations)) return false;
  }
  if (e.binder && e.binder->set && !isConstantExpr(*e.binder->set, allowObservations)) return false;
  return true;
}

bool checkTypes(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, const GlobalSymbols& symbols,
                DiagnosticEngine& diags) {
  const std::size_t before = diags.errorCount();
  detail::TypeChecker(types, symbols, diags).run(modules);
  return diags.errorCount() == before;
}

namespace detail {

bool isFamily(const Decl* d) {
  if (d == nullptr) return false;
  switch (d->kind) {
    case DeclKind::Var:
      return static_cast<const VarDecl*>(d)->index != nullptr;
    case DeclKind::Const:
      return static_cast<const ConstDecl*>(d)->index != nullptr;
    case DeclKind::Observe:
      return static_cast<const ObserveDecl*>(d)->index != nullptr;
    default:
      return false;
  }
}

const IndexSpec* indexOf(const Decl* d) {
  switch (d->kind) {
    case DeclKind::Var:
      return static_cast<const VarDecl*>(d)->index.get();
    case DeclKind::Const:
      return static_cast<const ConstDecl*>(d)->index.get();
    case DeclKind::Observe:
      return static_cast<const ObserveDecl*>(d)->index.get();
    default:
      return nullptr;
  }
}

void TypeChecker::run(const std::vector<std::unique_ptr<Module>>& modules) {
  for (const auto& m : modules)
    if (m->isStd) stdFiles_.insert(m->file);
  // Index sets and constants first: other declarations read their element types.
  for (const auto& m : modules) {
    for (auto& d : m->decls) {
      if (d->kind == DeclKind::Const) checkConst(static_cast<ConstDecl&>(*d));
      if (d->kind == DeclKind::Observe) checkIndex(static_cast<ObserveDecl&>(*d).index.get());
      if (d->kind == DeclKind::Var) checkIndex(static_cast<VarDecl&>(*d).index.get());
    }
  }
  for (const auto& m : modules) {
    for (auto& d : m->decls) checkTop(*d);
  }
  checkFunctions(modules);
}

void TypeChecker::checkTop(Decl& d) {
  switch (d.kind) {
    case DeclKind::Robot:
      checkRobot(static_cast<RobotDecl&>(d));
      break;
    case DeclKind::Clearance:
      checkClearance(static_cast<ClearanceDecl&>(d));
      break;
    case DeclKind::ItemSet:
      checkItems(static_cast<ItemsDecl&>(d));
      break;
    case DeclKind::Function: {
      auto& f = static_cast<FuncDecl&>(d);
      if (f.body) {
        const Type* t = check(f.body.get());
        if (f.result && f.result->resolved && !assignable(f.result->resolved, t)) {
          diags_.error("E0301", f.body->range,
                       fmt::format("function '{}' returns {}, but its body is {}", f.name.name,
                                   f.result->resolved->spelling, t->spelling));
        }
      }
      break;
    }
    case DeclKind::Var:
    case DeclKind::Require:
    case DeclKind::Sample:
    case DeclKind::Cost:
      checkScopeStmt(d);
      break;
    case DeclKind::Personal:
      checkPersonal(static_cast<PersonalDecl&>(d));
      break;
    case DeclKind::Skill:
      checkSkill(static_cast<SkillDecl&>(d));
      break;
    case DeclKind::Task:
      checkTask(static_cast<TaskDecl&>(d));
      break;
    default:
      break;
  }
}

}  // namespace detail
}  // namespace cbtl
