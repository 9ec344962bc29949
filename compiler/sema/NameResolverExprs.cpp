// resolve-names: names in expressions. A name is resolved in the scopes open where it appears; Enum.member
// and itemSet.entry are qualified names; quantifiers open a scope for their binders.
#include "compiler/sema/NameResolverInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

namespace cbtl::detail {

void NameResolver::resolveArgs(std::vector<Arg>& args) {
  for (auto& a : args) resolveExpr(a.value.get());
}

void NameResolver::resolveBinder(Binder& b) {
  resolveExpr(b.set.get());
  for (auto& bd : b.names) {
    Symbol s;
    s.kind = RefKind::Binder;
    s.binder = bd.get();
    bindLocal(bd->name, s);
  }
}

void NameResolver::resolveExpr(Expr* e) {
  if (e == nullptr) return;
  switch (e->kind) {
    case ExprKind::Name: {
      e->ref = lookupWithBinders(e->text, e->range);
      return;
    }
    case ExprKind::Member:
      resolveMember(e);
      return;
    case ExprKind::Call: {
      Expr* callee = e->operands[0].get();
      if (callee->kind == ExprKind::Name) {
        callee->ref = lookupWithBinders(callee->text, callee->range);
        e->ref = callee->ref;
      } else {
        resolveExpr(callee);
      }
      resolveArgs(e->args);
      return;
    }
    case ExprKind::Quantifier: {
      push();
      resolveBinder(*e->binder);
      resolveExpr(e->operands[0].get());
      resolveExpr(e->operands[1].get());
      pop();
      return;
    }
    default:
      for (auto& op : e->operands) resolveExpr(op.get());
      return;
  }
}

// object.member: resolves the object; its fields are checked by check-types, unless the member is part of a
// qualified name.
void NameResolver::resolveMember(Expr* e) {
  Expr* object = e->operands[0].get();
  if (object->kind == ExprKind::Name) {
    // Enum.member and itemSet.entry are qualified names, not field accesses.
    NameRef base = lookupWithBinders(object->text, object->range, /*report=*/false);
    if (base.kind == RefKind::EnumType) {
      object->ref = base;
      const auto* en = static_cast<const EnumDecl*>(base.decl);
      for (std::size_t i = 0; i < en->members.size(); ++i) {
        if (en->members[i].name == e->text) {
          e->ref = NameRef{RefKind::EnumMember, en, nullptr, static_cast<int>(i)};
          return;
        }
      }
      std::vector<std::string> names;
      for (const auto& m : en->members) names.push_back(m.name);
      Diagnostic& d =
          diags_.error("E0208", e->nameRange, fmt::format("enum '{}' has no member '{}'", en->name.name, e->text));
      const std::string guess = closestMatch(e->text, names);
      if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
      return;
    }
    if (base.kind == RefKind::ItemSet) {
      object->ref = base;
      const auto* items = static_cast<const ItemsDecl*>(base.decl);
      for (std::size_t i = 0; i < items->entries.size(); ++i) {
        if (items->entries[i].name.name == e->text) {
          e->ref = NameRef{RefKind::ItemEntry, items, nullptr, static_cast<int>(i)};
          return;
        }
      }
      // Not an entry: fall through to field access on the set (reported by the type checker).
    }
  }
  resolveExpr(object);
}

}  // namespace cbtl::detail
