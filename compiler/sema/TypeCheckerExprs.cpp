// check-types: expression typing. Every expression gets a type in Expr::type; int widens to real.
#include "compiler/sema/TypeCheckerInternal.h"

#include "compiler/sema/TypeChecker.h"
#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace cbtl::detail {

const Type* TypeChecker::check(Expr* e, bool allowFamily) {
  if (e == nullptr) return err();
  e->type = checkInner(*e, allowFamily);
  return e->type;
}

const Type* TypeChecker::checkInner(Expr& e, bool allowFamily) {
  switch (e.kind) {
    case ExprKind::Number:
      if (e.text == "<missing>") return err();
      return e.text.find_first_of(".eE") == std::string::npos ? types_.integer() : types_.real();
    case ExprKind::String:
      return types_.text();
    case ExprKind::Bool:
      return types_.boolean();
    case ExprKind::Name:
      return nameType(e, allowFamily);
    case ExprKind::Member:
      return memberType(e);
    case ExprKind::Call:
      return callType(e);
    case ExprKind::Index:
      return indexType(e);
    case ExprKind::Unary: {
      const Type* t = check(e.operands[0].get());
      if (t->isError()) return t;
      if (e.unaryOp == UnaryOp::Neg && (t->isNumeric() || t->kind == TypeKind::Vec)) return t;
      if (e.unaryOp == UnaryOp::Not && t->kind == TypeKind::Bool) return t;
      diags_.error("E0303", e.range,
                   fmt::format("operator '{}' does not apply to {}", toString(e.unaryOp), t->spelling));
      return err();
    }
    case ExprKind::Binary:
      return binaryType(e);
    case ExprKind::Range: {
      const Type* a = check(e.operands[0].get());
      const Type* b = check(e.operands[1].get());
      if (a->isError() || b->isError()) return err();
      if (!a->isNumeric() || !b->isNumeric()) {
        diags_.error("E0303", e.range, fmt::format("a range needs numbers, not {} and {}", a->spelling, b->spelling));
        return err();
      }
      return types_.rangeOf(numericResult(a, b));
    }
    case ExprKind::In:
      return inType(e);
    case ExprKind::Quantifier: {
      bindBinder(*e.binder, "a quantifier's domain");
      if (e.operands[0]) expect(e.operands[0].get(), types_.boolean(), "a 'where' condition");
      expect(e.operands[1].get(), types_.boolean(), "a quantifier's body");
      return types_.boolean();
    }
    case ExprKind::If: {
      expect(e.operands[0].get(), types_.boolean(), "an 'if' condition");
      const Type* a = check(e.operands[1].get());
      const Type* b = check(e.operands[2].get());
      if (a->isError() || b->isError()) return err();
      if (a == b) return a;
      if (a->isNumeric() && b->isNumeric()) return numericResult(a, b);
      diags_.error("E0301", e.range,
                   fmt::format("the branches of 'if' have different types, {} and {}", a->spelling, b->spelling));
      return err();
    }
    case ExprKind::Tuple: {
      std::vector<const Type*> elems;
      for (auto& op : e.operands) elems.push_back(check(op.get()));
      return types_.tuple(std::move(elems));
    }
    case ExprKind::List:
      return listType(e);
  }
  return err();
}

// A family member (one index of the family's index type) or a vec component (an int index).
const Type* TypeChecker::indexType(Expr& e) {
  Expr* base = e.operands[0].get();
  const Type* bt = check(base, /*allowFamily=*/true);
  std::vector<const Type*> idx;
  for (std::size_t i = 1; i < e.operands.size(); ++i) idx.push_back(check(e.operands[i].get()));
  if (bt->isError()) return err();
  if (base->kind == ExprKind::Name && isFamily(base->ref.decl)) {
    const IndexSpec* spec = indexOf(base->ref.decl);
    if (idx.size() != 1) {
      diags_.error("E0306", e.range, fmt::format("'{}' has one index", base->text));
      return err();
    }
    if (spec->elementType && !assignable(spec->elementType, idx[0])) {
      diags_.error("E0306", e.operands[1]->range,
                   fmt::format("'{}' is indexed by {}, but this index is {}", base->text, spec->elementType->spelling,
                               idx[0]->spelling));
      return err();
    }
    return bt;
  }
  if (bt->kind == TypeKind::Vec && idx.size() == 1 && idx[0]->kind == TypeKind::Int) return types_.real();
  diags_.error("E0306", e.range, fmt::format("a value of type {} cannot be indexed", bt->spelling));
  return err();
}

// Membership in a range (of numbers) or a set (of its element type); always bool.
const Type* TypeChecker::inType(Expr& e) {
  const Type* a = check(e.operands[0].get());
  const Type* s = check(e.operands[1].get());
  if (a->isError() || s->isError()) return types_.boolean();
  if (s->kind == TypeKind::Range) {
    if (!a->isNumeric())
      diags_.error("E0303", e.range, fmt::format("'in' a range needs a number, not {}", a->spelling));
  } else if (s->kind == TypeKind::Set) {
    if (!assignable(s->element, a) && !(a->isNumeric() && s->element->isNumeric())) {
      diags_.error("E0303", e.range, fmt::format("{} cannot be a member of {}", a->spelling, s->spelling));
    }
  } else {
    diags_.error("E0303", e.operands[1]->range, fmt::format("'in' needs a range or a set, not {}", s->spelling));
  }
  return types_.boolean();
}

// A list is a set of its elements' type: numbers widen to real, and ranges of int and of real may be mixed
// (the first element's type is kept).
const Type* TypeChecker::listType(Expr& e) {
  const Type* elem = nullptr;
  for (auto& op : e.operands) {
    const Type* t = check(op.get());
    if (t->isError()) return err();
    if (elem == nullptr) {
      elem = t;
    } else if (elem != t) {
      if (elem->isNumeric() && t->isNumeric()) {
        elem = types_.real();
      } else if (elem->kind != TypeKind::Range || t->kind != TypeKind::Range) {
        diags_.error("E0301", op->range,
                     fmt::format("list elements must have one type; this is {}, earlier ones are {}", t->spelling,
                                 elem->spelling));
        return err();
      }
    }
  }
  return types_.setOf(elem ? elem : types_.error());
}

const Type* TypeChecker::paramType(const NameRef& r) {
  if (r.decl == nullptr || r.index < 0) return err();
  switch (r.decl->kind) {
    case DeclKind::Function:
    case DeclKind::Sampler:
    case DeclKind::Action: {
      const auto& c = static_cast<const CallableDecl&>(*r.decl);
      return c.params.at(r.index).type.resolved ? c.params.at(r.index).type.resolved : err();
    }
    case DeclKind::Personal: {
      const auto& p = static_cast<const PersonalDecl&>(*r.decl);
      return p.params.at(r.index).type.resolved ? p.params.at(r.index).type.resolved : err();
    }
    case DeclKind::Skill: {
      const auto& s = static_cast<const SkillDecl&>(*r.decl);
      return s.params.at(r.index).type.resolved ? s.params.at(r.index).type.resolved : err();
    }
    default:
      return err();
  }
}

const Type* TypeChecker::nameType(Expr& e, bool allowFamily) {
  const NameRef& r = e.ref;
  switch (r.kind) {
    case RefKind::Unresolved:
      return err();
    case RefKind::Const:
    case RefKind::Variable:
    case RefKind::Observation: {
      if (isFamily(r.decl) && !allowFamily) {
        diags_.error("E0306", e.range,
                     fmt::format("'{}' is an indexed family; give an index, as in {}[...]", e.text, e.text));
        return err();
      }
      if (r.kind == RefKind::Const) return constType(e, static_cast<const ConstDecl&>(*r.decl));
      const Type* t = declaredType(*r.decl);
      return t ? t : err();
    }
    case RefKind::EnumType:
      return types_.setOf(types_.enumType(static_cast<const EnumDecl*>(r.decl), r.decl->name.name));
    case RefKind::EnumMember:
      return types_.enumType(static_cast<const EnumDecl*>(r.decl), r.decl->name.name);
    case RefKind::ItemSet: {
      const auto* items = static_cast<const ItemsDecl*>(r.decl);
      return items->itemType.resolved ? types_.setOf(items->itemType.resolved) : err();
    }
    case RefKind::ItemEntry: {
      const auto* items = static_cast<const ItemsDecl*>(r.decl);
      return items->itemType.resolved ? items->itemType.resolved : err();
    }
    case RefKind::Param:
      return paramType(r);
    case RefKind::Binder:
      return r.binder && r.binder->type ? r.binder->type : err();
    case RefKind::Builtin:
      if (r.index == static_cast<int>(BuiltinId::Pi)) return types_.real();
      diags_.error("E0313", e.range,
                   fmt::format("'{}' can only be used in a {}", e.text,
                               r.index == static_cast<int>(BuiltinId::Box) ? "domain" : "sample statement"));
      return err();
    case RefKind::Function:
    case RefKind::Sampler:
    case RefKind::Action:
    case RefKind::Feedback: {
      const std::string kind = toString(r.decl->kind);
      const char* article = std::string_view("aeiou").find(kind.front()) != std::string_view::npos ? "an" : "a";
      diags_.error("E0207", e.range, fmt::format("'{}' is {} {} and cannot be used as a value", e.text, article, kind));
      return err();
    }
  }
  return err();
}

const Type* TypeChecker::memberType(Expr& e) {
  if (e.ref.kind == RefKind::EnumMember || e.ref.kind == RefKind::ItemEntry) return nameType(e, false);
  // `Enum.unknown` was reported by name resolution (E0208 with a did-you-mean); it is not a field access.
  const Expr* object = e.operands[0].get();
  if (object->kind == ExprKind::Name && object->ref.kind == RefKind::EnumType) return err();
  const Type* t = check(e.operands[0].get());
  if (t->isError()) return t;
  const std::string& m = e.text;
  std::vector<std::string> fields;
  switch (t->kind) {
    case TypeKind::Vec: {
      static const char* names[] = {"x", "y", "z"};
      for (int i = 0; i < std::min(3, t->size); ++i) {
        if (m == names[i]) return types_.real();
        fields.push_back(names[i]);
      }
      break;
    }
    case TypeKind::SE2:
      if (m == "x" || m == "y" || m == "yaw") return types_.real();
      fields = {"x", "y", "yaw"};
      break;
    case TypeKind::SE3:
      if (m == "x" || m == "y" || m == "z") return types_.real();
      if (m == "position") return types_.vec(3);
      fields = {"x", "y", "z", "position"};
      break;
    case TypeKind::Item:
      for (const auto& f : t->itemDecl->fields) {
        if (f.name.name == m) return f.type.resolved ? f.type.resolved : err();
        fields.push_back(f.name.name);
      }
      break;
    default:
      break;
  }
  Diagnostic& d = diags_.error("E0208", e.nameRange.valid() ? e.nameRange : e.range,
                               fmt::format("{} has no member '{}'", t->spelling, m));
  const std::string guess = closestMatch(m, fields);
  if (!guess.empty())
    d.help(fmt::format("did you mean '{}'?", guess));
  else if (!fields.empty()) {
    std::string list;
    for (std::size_t i = 0; i < fields.size(); ++i) list += (i ? ", " : "") + fields[i];
    d.help(fmt::format("its members are: {}", list));
  }
  return err();
}

const Type* TypeChecker::numericResult(const Type* a, const Type* b) {
  return (a->kind == TypeKind::Int && b->kind == TypeKind::Int) ? types_.integer() : types_.real();
}

const Type* TypeChecker::binaryType(Expr& e) {
  const Type* a = check(e.operands[0].get());
  const Type* b = check(e.operands[1].get());
  if (a->isError() || b->isError()) return err();
  const BinaryOp op = e.binaryOp;
  auto isComparison = [](const Expr& x) {
    return x.kind == ExprKind::Binary && (x.binaryOp == BinaryOp::Lt || x.binaryOp == BinaryOp::Le ||
                                          x.binaryOp == BinaryOp::Gt || x.binaryOp == BinaryOp::Ge);
  };
  auto fail = [&]() {
    Diagnostic& d =
        diags_.error("E0303", e.range,
                     fmt::format("operator '{}' does not apply to {} and {}", toString(op), a->spelling, b->spelling));
    if (isComparison(e) && isComparison(*e.operands[0])) {
      d.help("comparisons do not chain: write 'a < b and b < c' instead of 'a < b < c'");
    }
    return err();
  };
  switch (op) {
    case BinaryOp::Add:
    case BinaryOp::Sub:
      if (a->isNumeric() && b->isNumeric()) return numericResult(a, b);
      if (a->kind == TypeKind::Vec && a == b) return a;
      if (op == BinaryOp::Add && a->kind == TypeKind::Text && b->kind == TypeKind::Text) return a;
      return fail();
    case BinaryOp::Mul:
      if (a->isNumeric() && b->isNumeric()) return numericResult(a, b);
      if (a->kind == TypeKind::Vec && b->isNumeric()) return a;
      if (b->kind == TypeKind::Vec && a->isNumeric()) return b;
      return fail();
    case BinaryOp::Div:
      if (a->isNumeric() && b->isNumeric()) return types_.real();
      if (a->kind == TypeKind::Vec && b->isNumeric()) return a;
      return fail();
    case BinaryOp::Mod:
      if (a->kind == TypeKind::Int && b->kind == TypeKind::Int) return a;
      if (a->isNumeric() && b->isNumeric()) return types_.real();
      return fail();
    case BinaryOp::Pow:
      if (a->isNumeric() && b->isNumeric()) return types_.real();
      return fail();
    case BinaryOp::Eq:
    case BinaryOp::Ne:
      if (a == b || (a->isNumeric() && b->isNumeric())) return types_.boolean();
      return fail();
    case BinaryOp::Lt:
    case BinaryOp::Le:
    case BinaryOp::Gt:
    case BinaryOp::Ge:
      if (a->isNumeric() && b->isNumeric()) return types_.boolean();
      return fail();
    case BinaryOp::And:
    case BinaryOp::Or:
    case BinaryOp::Implies:
    case BinaryOp::Iff:
      if (a->kind == TypeKind::Bool && b->kind == TypeKind::Bool) return a;
      return fail();
  }
  return fail();
}

const Type* TypeChecker::elementOf(const Type* collection, const Expr& at, const char* what) {
  if (collection->isError()) return collection;
  if (collection->kind == TypeKind::Set) return collection->element;
  if (collection->kind == TypeKind::Range) {
    if (collection->element->kind == TypeKind::Int) return collection->element;
    diags_
        .error("E0301", at.range,
               fmt::format("{} must be a finite set; a range of reals has infinitely many values", what))
        .help("use an integer range such as 0 .. 3, an enum, an item set or a list");
    return err();
  }
  diags_.error(
      "E0301", at.range,
      fmt::format("{} must be a set, an enum, an integer range or a list, not {}", what, collection->spelling));
  return err();
}

void TypeChecker::bindBinder(Binder& b, const char* what) {
  const Type* set = check(b.set.get());
  const Type* elem = elementOf(set, *b.set, what);
  for (auto& n : b.names) n->type = elem;
}

const Type* TypeChecker::expect(Expr* e, const Type* want, const char* context) {
  const Type* got = check(e);
  if (!assignable(want, got)) {
    diags_.error("E0301", e->range,
                 fmt::format("{} must be {}, but this is {}", context, want->spelling, got->spelling));
  }
  return got;
}

}  // namespace cbtl::detail
