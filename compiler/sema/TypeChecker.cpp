#include "compiler/sema/TypeChecker.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string_view>

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

namespace {

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

class Checker {
 public:
  Checker(TypeContext& types, const GlobalSymbols& symbols, DiagnosticEngine& diags)
      : types_(types), symbols_(symbols), diags_(diags) {}

  void run(const std::vector<std::unique_ptr<Module>>& modules) {
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
    checkRecursion(modules);
  }

 private:
  const Type* err() { return types_.error(); }

  // --- expressions --------------------------------------------------------------------------

  const Type* paramType(const NameRef& r) {
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

  const Type* nameType(Expr& e, bool allowFamily) {
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
        diags_.error("E0207", e.range,
                     fmt::format("'{}' is {} {} and cannot be used as a value", e.text, article, kind));
        return err();
      }
    }
    return err();
  }

  const Type* elementOf(const Type* collection, const Expr& at, const char* what) {
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

  void bindBinder(Binder& b, const char* what) {
    const Type* set = check(b.set.get());
    const Type* elem = elementOf(set, *b.set, what);
    for (auto& n : b.names) n->type = elem;
  }

  const Type* expect(Expr* e, const Type* want, const char* context) {
    const Type* got = check(e);
    if (!assignable(want, got)) {
      diags_.error("E0301", e->range,
                   fmt::format("{} must be {}, but this is {}", context, want->spelling, got->spelling));
    }
    return got;
  }

  const Type* memberType(Expr& e) {
    if (e.ref.kind == RefKind::EnumMember || e.ref.kind == RefKind::ItemEntry) return nameType(e, false);
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

  // Matches call arguments to parameters (positional first, then named). Returns false on a mismatch
  // already reported. `order[i]` is the argument for parameter i.
  bool matchArgs(const std::string& what, const std::string& name, const std::vector<Param>& params,
                 std::vector<Arg>& args, SourceRange at, SourceRange declAt, std::vector<Arg*>& order) {
    order.assign(params.size(), nullptr);
    bool ok = true;
    bool sawNamed = false;
    std::size_t positional = 0;
    for (auto& a : args) {
      if (a.name.name.empty()) {
        if (sawNamed) {
          diags_.error("E0307", a.range, "a positional argument cannot follow a named one");
          ok = false;
          continue;
        }
        if (positional >= params.size()) {
          diags_
              .error("E0302", a.range,
                     fmt::format("{} '{}' takes {} argument{}, but {} were given", what, name, params.size(),
                                 params.size() == 1 ? "" : "s", args.size()))
              .note("declared here", declAt);
          return false;
        }
        order[positional++] = &a;
        continue;
      }
      sawNamed = true;
      std::size_t i = 0;
      for (; i < params.size(); ++i) {
        if (params[i].name.name == a.name.name) break;
      }
      if (i == params.size()) {
        std::vector<std::string> names;
        for (const auto& p : params) names.push_back(p.name.name);
        Diagnostic& d = diags_.error("E0307", a.name.range,
                                     fmt::format("{} '{}' has no parameter named '{}'", what, name, a.name.name));
        const std::string guess = closestMatch(a.name.name, names);
        if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
        ok = false;
        continue;
      }
      if (order[i] != nullptr) {
        diags_.error("E0307", a.name.range, fmt::format("argument '{}' is given twice", a.name.name));
        ok = false;
        continue;
      }
      order[i] = &a;
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (order[i] == nullptr && ok) {
        diags_
            .error("E0302", at,
                   fmt::format("{} '{}' takes {} argument{}; '{}' is missing", what, name, params.size(),
                               params.size() == 1 ? "" : "s", params[i].name.name))
            .note("declared here", declAt);
        return false;
      }
    }
    return ok;
  }

  // Checks a call against a callable declaration; returns the (substituted) result type.
  const Type* checkCallable(const CallableDecl& c, std::vector<Arg>& args, SourceRange at) {
    std::vector<Arg*> order;
    for (auto& a : args) check(a.value.get());
    if (!matchArgs(toString(c.kind), c.name.name, c.params, args, at, c.name.range, order)) return err();
    Unifier unifier(types_);
    bool ok = true;
    for (std::size_t i = 0; i < c.params.size(); ++i) {
      const Type* formal = c.params[i].type.resolved;
      const Type* actual = order[i]->value->type;
      if (formal == nullptr || actual == nullptr) continue;
      if (!unifier.unify(formal, actual)) {
        diags_
            .error("E0301", order[i]->value->range,
                   fmt::format("argument '{}' of '{}' must be {}, but this is {}", c.params[i].name.name, c.name.name,
                               unifier.substitute(formal)->spelling, actual->spelling))
            .note("declared here", c.params[i].name.range);
        ok = false;
      }
    }
    if (!ok) return err();
    if (!c.result || !c.result->resolved) return types_.voidType();
    const Type* result = unifier.substitute(c.result->resolved);
    if (result->isGeneric()) {
      diags_.error("E0301", at,
                   fmt::format("cannot infer the result type {} of '{}' from its arguments",
                               c.result->resolved->spelling, c.name.name));
      return err();
    }
    return result;
  }

  const Type* callType(Expr& e) {
    Expr* callee = e.operands[0].get();
    if (callee->kind != ExprKind::Name) {
      diags_.error("E0313", callee->range, "only named functions can be called");
      for (auto& a : e.args) check(a.value.get());
      return err();
    }
    const NameRef& r = callee->ref;
    if (r.kind == RefKind::Unresolved) {
      for (auto& a : e.args) check(a.value.get());
      return err();
    }
    if (r.kind == RefKind::Function) return checkCallable(static_cast<const CallableDecl&>(*r.decl), e.args, e.range);
    if (r.kind == RefKind::Builtin && r.index == static_cast<int>(BuiltinId::Box)) {
      if (!inDomain_) {
        diags_.error("E0313", callee->range,
                     "box(...) describes a domain; use it after 'in' in a variable declaration");
      }
      for (auto& a : e.args) check(a.value.get());
      return types_.voidType();
    }
    for (auto& a : e.args) check(a.value.get());
    const char* hint = r.kind == RefKind::Sampler  ? "samplers are used in 'sample x ~ name(...);'"
                       : r.kind == RefKind::Action ? "actions are called in a skill's 'do' block"
                                                   : "only functions can be called in expressions";
    diags_.error("E0313", callee->range, fmt::format("'{}' cannot be called here", callee->text)).help(hint);
    return err();
  }

  const Type* numericResult(const Type* a, const Type* b) {
    return (a->kind == TypeKind::Int && b->kind == TypeKind::Int) ? types_.integer() : types_.real();
  }

  const Type* binaryType(Expr& e) {
    const Type* a = check(e.operands[0].get());
    const Type* b = check(e.operands[1].get());
    if (a->isError() || b->isError()) return err();
    const BinaryOp op = e.binaryOp;
    auto isComparison = [](const Expr& x) {
      return x.kind == ExprKind::Binary && (x.binaryOp == BinaryOp::Lt || x.binaryOp == BinaryOp::Le ||
                                            x.binaryOp == BinaryOp::Gt || x.binaryOp == BinaryOp::Ge);
    };
    auto fail = [&]() {
      Diagnostic& d = diags_.error(
          "E0303", e.range,
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

 public:
  const Type* check(Expr* e, bool allowFamily = false) {
    if (e == nullptr) return err();
    e->type = checkInner(*e, allowFamily);
    return e->type;
  }

 private:
  const Type* checkInner(Expr& e, bool allowFamily) {
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
      case ExprKind::Index: {
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
                         fmt::format("'{}' is indexed by {}, but this index is {}", base->text,
                                     spec->elementType->spelling, idx[0]->spelling));
            return err();
          }
          return bt;
        }
        if (bt->kind == TypeKind::Vec && idx.size() == 1 && idx[0]->kind == TypeKind::Int) return types_.real();
        diags_.error("E0306", e.range, fmt::format("a value of type {} cannot be indexed", bt->spelling));
        return err();
      }
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
      case ExprKind::In: {
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
      case ExprKind::List: {
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
    }
    return err();
  }

  // --- declarations -------------------------------------------------------------------------

  void checkIndex(IndexSpec* index) {
    if (index == nullptr || index->elementType != nullptr) return;
    const Type* set = check(index->set.get());
    index->elementType = elementOf(set, *index->set, "an index set");
    if (!index->elementType->isError() && !isConstantExpr(*index->set, false)) {
      diags_.error("E0305", index->set->range, "an index set must be known at compile time");
    }
  }

  // Constants are checked on first use, so a constant may be used before its declaration. One that is
  // reached again while its own value is being checked is defined in terms of itself (E0316, reported once).
  const Type* constType(const Expr& use, const ConstDecl& c) {
    if (c.valueType == nullptr) {
      if (constsInProgress_.count(&c)) {
        if (constCyclesReported_.insert(&c).second) {
          diags_.error("E0316", c.name.range, fmt::format("constant '{}' is defined in terms of itself", c.name.name))
              .note("through this use", use.range);
        }
        return err();
      }
      // Name references point at const declarations; the checker owns the AST it annotates.
      checkConst(const_cast<ConstDecl&>(c));
    }
    return c.valueType != nullptr ? c.valueType : err();
  }

  void checkConst(ConstDecl& c) {
    if (c.valueType != nullptr || constsInProgress_.count(&c)) return;
    constsInProgress_.insert(&c);
    checkConstValue(c);
    constsInProgress_.erase(&c);
  }

  // The number of members of an index set when it is evident from the source (an enum, an item set, a
  // list, or a range of integer literals); nullopt otherwise (lowering enumerates the rest).
  static std::optional<std::size_t> indexSetSize(const Expr* set) {
    if (set == nullptr) return std::nullopt;
    if (set->kind == ExprKind::Name && set->ref.kind == RefKind::EnumType) {
      return static_cast<const EnumDecl*>(set->ref.decl)->members.size();
    }
    if (set->kind == ExprKind::Name && set->ref.kind == RefKind::ItemSet) {
      return static_cast<const ItemsDecl*>(set->ref.decl)->entries.size();
    }
    if (set->kind == ExprKind::List) return set->operands.size();
    if (set->kind == ExprKind::Range) {
      auto literal = [](const Expr* x) -> std::optional<double> {
        double sign = 1;
        if (x->kind == ExprKind::Unary && x->unaryOp == UnaryOp::Neg) {
          sign = -1;
          x = x->operands[0].get();
        }
        if (x->kind != ExprKind::Number || x->text.find_first_of(".eE<") != std::string::npos) return std::nullopt;
        return sign * x->number;
      };
      const auto lo = literal(set->operands[0].get()), hi = literal(set->operands[1].get());
      if (lo && hi && *hi >= *lo && *hi - *lo < 1e9) return static_cast<std::size_t>(*hi - *lo) + 1;
    }
    return std::nullopt;
  }

  void checkConstValue(ConstDecl& c) {
    checkIndex(c.index.get());
    const Type* t = check(c.value.get());
    if (c.value && !isConstantExpr(*c.value, false)) {
      diags_.error("E0305", c.value->range,
                   fmt::format("the value of constant '{}' must not depend on variables or observations", c.name.name));
    }
    if (c.index) {
      if (c.value && c.value->kind != ExprKind::List) {
        diags_.error("E0312", c.value->range, "an indexed constant needs a list with one value per index");
        c.valueType = err();
        return;
      }
      if (const auto size = indexSetSize(c.index->set.get()); c.value && size && *size != c.value->operands.size()) {
        diags_
            .error("E0312", c.value->range,
                   fmt::format("constant '{}' has {} value{}, but its index set has {} member{}", c.name.name,
                               c.value->operands.size(), c.value->operands.size() == 1 ? "" : "s", *size,
                               *size == 1 ? "" : "s"))
            .note("the index set", c.index->set->range);
      }
      t = t->kind == TypeKind::Set ? t->element : err();
    }
    if (c.type && c.type->resolved && !c.type->resolved->isError()) {
      if (!assignable(c.type->resolved, t)) {
        diags_.error("E0315", c.value->range,
                     fmt::format("constant '{}' is declared {}, but its value is {}", c.name.name,
                                 c.type->resolved->spelling, t->spelling));
      }
      t = c.type->resolved;
    }
    c.valueType = t;
  }

  void checkDomain(VarDecl& v) {
    const Type* t = v.type.resolved;
    Expr* d = v.domain.get();
    if (t == nullptr || t->isError()) {
      check(d);
      return;
    }
    if (!t->isVariableType()) {
      diags_.error("E0304", v.type.range, fmt::format("a variable cannot have type {}", t->spelling))
          .help("variables are real, int, bool, text, vec<N>, SE2, SE3, Conf<R>, an enum or an item type");
      return;
    }
    if (d == nullptr) return;
    inDomain_ = true;
    const Type* dt = check(d);
    inDomain_ = false;
    if (dt->isError()) return;
    if (!isConstantExpr(*d, /*allowObservations=*/true)) {
      diags_.error("E0305", d->range, "a domain may depend on constants and observations, not on variables");
      return;
    }
    auto bad = [&](const std::string& form) {
      diags_.error("E0304", d->range, fmt::format("the domain of a {} variable is written {}", t->spelling, form));
    };
    auto isRangeList = [&](std::size_t n) {
      return d->kind == ExprKind::List && d->operands.size() == n &&
             std::all_of(d->operands.begin(), d->operands.end(),
                         [](const ExprPtr& x) { return x->type && x->type->kind == TypeKind::Range; });
    };
    auto checkBox = [&](const std::vector<std::string>& names) {
      if (d->kind != ExprKind::Call || d->ref.kind != RefKind::Builtin) return false;
      std::set<std::string> seen;
      for (const auto& a : d->args) {
        if (std::find(names.begin(), names.end(), a.name.name) == names.end() || !seen.insert(a.name.name).second) {
          diags_.error("E0304", a.range,
                       fmt::format("box(...) for {} takes named ranges {}", t->spelling,
                                   fmt::format("{}", fmt::join(names, ", "))));
          return true;
        }
        if (!a.value->type || a.value->type->kind != TypeKind::Range) {
          diags_.error("E0304", a.range, fmt::format("'{}' must be a range lo .. hi", a.name.name));
        }
      }
      return true;
    };
    switch (t->kind) {
      case TypeKind::Real:
      case TypeKind::Int:
        if (dt->kind != TypeKind::Range)
          bad("lo .. hi");
        else if (t->kind == TypeKind::Int && dt->element->kind != TypeKind::Int)
          bad("with whole-number bounds, lo .. hi");
        break;
      case TypeKind::Vec:
        if (checkBox({"x", "y", "z"})) break;
        if (!isRangeList(static_cast<std::size_t>(t->size)))
          bad(fmt::format("as a list of {} ranges, [lo .. hi, ...]", t->size));
        break;
      case TypeKind::SE2:
        if (!checkBox({"x", "y", "yaw"})) bad("box(x: lo .. hi, y: lo .. hi, yaw: lo .. hi)");
        break;
      case TypeKind::SE3:
        if (!checkBox({"x", "y", "z"})) bad("box(x: lo .. hi, y: lo .. hi, z: lo .. hi)");
        break;
      case TypeKind::Enum:
      case TypeKind::Item:
      case TypeKind::Text:
      case TypeKind::Bool:
        if (dt->kind != TypeKind::Set || !assignable(t, dt->element)) {
          bad(fmt::format("as a set of {} values (a list, an item set or an observed set)", t->spelling));
        }
        break;
      case TypeKind::Conf:
        bad("without 'in': the robot's joint limits are its domain");
        break;
      default:
        break;
    }
  }

  void checkVar(VarDecl& v) {
    checkIndex(v.index.get());
    checkDomain(v);
    if (v.init) {
      const Type* it = check(v.init.get());
      if (v.type.resolved && !assignable(v.type.resolved, it)) {
        diags_.error("E0315", v.init->range,
                     fmt::format("the initial value of '{}' must be {}, but this is {}", v.name.name,
                                 v.type.resolved->spelling, it->spelling));
      } else if (!isConstantExpr(*v.init, true)) {
        diags_.error("E0305", v.init->range, "an initial value may depend on constants and observations only");
      }
    }
  }

  // Sample targets must be variables (or members of variable families) of the scope being checked.
  const Type* sampleTarget(Expr* t) {
    Expr* base = t->kind == ExprKind::Index ? t->operands[0].get() : t;
    if (base->kind != ExprKind::Name || base->ref.kind != RefKind::Variable) {
      check(t, true);
      if (base->ref.kind != RefKind::Unresolved) {
        diags_.error("E0310", t->range, "a sample statement writes variables; this is not a variable");
      }
      return err();
    }
    return check(t, /*allowFamily=*/true);
  }

  void checkSample(SampleDecl& s) {
    if (s.forBinder) bindBinder(*s.forBinder, "a 'for' domain");
    std::vector<const Type*> targets;
    for (auto& t : s.targets) targets.push_back(sampleTarget(t.get()));
    if (s.samplerRef.kind == RefKind::Builtin) {  // uniform over each target's domain
      if (!s.args.empty()) diags_.error("E0310", s.args.front().range, "'uniform' takes no arguments");
      return;
    }
    if (s.samplerRef.kind != RefKind::Sampler) {
      for (auto& a : s.args) check(a.value.get());
      return;
    }
    const auto& decl = static_cast<const CallableDecl&>(*s.samplerRef.decl);
    const Type* result = checkCallable(decl, s.args, s.range);
    if (result->isError()) return;
    const Type* want = targets.size() == 1 ? targets[0] : types_.tuple(targets);
    for (const Type* t : targets) {
      if (t->isError()) return;
    }
    if (!assignable(want, result)) {
      diags_.error("E0310", s.sampler.range,
                   fmt::format("sampler '{}' produces {}, but the target{} {} {}", s.sampler.name, result->spelling,
                               targets.size() == 1 ? "" : "s", targets.size() == 1 ? "is" : "are", want->spelling));
    }
  }

  void checkScopeStmt(Decl& d) {
    switch (d.kind) {
      case DeclKind::Var:
        checkVar(static_cast<VarDecl&>(d));
        break;
      case DeclKind::Require: {
        auto& r = static_cast<RequireDecl&>(d);
        const Type* t = check(r.condition.get());
        if (!t->isError() && t->kind != TypeKind::Bool) {
          diags_.error("E0301", r.condition->range,
                       fmt::format("a constraint must be bool, but this is {}", t->spelling));
        }
        break;
      }
      case DeclKind::Sample:
        checkSample(static_cast<SampleDecl&>(d));
        break;
      case DeclKind::Cost: {
        auto& c = static_cast<CostDecl&>(d);
        const Type* t = check(c.value.get());
        if (!t->isError() && !t->isNumeric()) {
          diags_.error("E0301", c.value->range, fmt::format("a cost must be a number, but this is {}", t->spelling));
        }
        break;
      }
      default:
        break;
    }
  }

  void checkActions(std::vector<std::unique_ptr<ActionStmt>>& stmts) {
    for (auto& s : stmts) {
      switch (s->kind) {
        case ActionStmtKind::Call:
          if (s->calleeRef.kind == RefKind::Action) {
            checkCallable(static_cast<const CallableDecl&>(*s->calleeRef.decl), s->args, s->range);
          } else {
            for (auto& a : s->args) check(a.value.get());
          }
          break;
        case ActionStmtKind::For:
          bindBinder(*s->forBinder, "a 'for' domain");
          checkActions(s->body);
          break;
        case ActionStmtKind::If:
          expect(s->condition.get(), types_.boolean(), "an 'if' condition");
          checkActions(s->body);
          checkActions(s->elseBody);
          break;
        case ActionStmtKind::Block:
          checkActions(s->body);
          break;
      }
    }
  }

  void checkTask(TaskDecl& t) {
    for (auto& d : t.body) checkScopeStmt(*d);
    std::map<std::string, SourceRange> names;
    for (auto& inst : t.instances) {
      for (auto& a : inst.args) check(a.value.get());
      const std::string& instName = inst.instanceName();
      if (auto it = names.find(instName); it != names.end()) {
        if (inst.alias.name.empty()) {
          diags_
              .error("E0501", inst.range,
                     fmt::format("skill '{}' runs twice in task '{}'", inst.skill.name, t.name.name))
              .help(fmt::format("name this instance: {} as {}2", inst.skill.name, inst.skill.name))
              .note("first run here", it->second);
        } else {
          diags_
              .error("E0504", inst.alias.range,
                     fmt::format("instance name '{}' is used twice in task '{}'", instName, t.name.name))
              .note("first used here", it->second);
        }
        continue;
      }
      names.emplace(instName, inst.range);
      if (inst.skillDecl == nullptr) continue;
      const auto& params = inst.skillDecl->params;
      if (inst.args.size() != params.size()) {
        diags_
            .error("E0502", inst.range,
                   fmt::format("skill '{}' takes {} argument{}, but {} {} given", inst.skill.name, params.size(),
                               params.size() == 1 ? "" : "s", inst.args.size(), inst.args.size() == 1 ? "is" : "are"))
            .note("declared here", inst.skillDecl->name.range);
        continue;
      }
      for (std::size_t i = 0; i < params.size(); ++i) {
        Arg& a = inst.args[i];
        const bool isVar =
            a.value->kind == ExprKind::Name && a.value->ref.kind == RefKind::Variable && !isFamily(a.value->ref.decl);
        const bool isMember = a.value->kind == ExprKind::Index && a.value->operands[0]->kind == ExprKind::Name &&
                              a.value->operands[0]->ref.kind == RefKind::Variable;
        if (!isVar && !isMember) {
          diags_
              .error(
                  "E0502", a.range,
                  fmt::format("argument '{}' of skill '{}' must be a variable", params[i].name.name, inst.skill.name))
              .help("skill parameters share a task variable with the skill; declare one with 'var'");
          continue;
        }
        if (params[i].type.resolved && a.value->type && !a.value->type->isError() &&
            params[i].type.resolved != a.value->type) {
          diags_.error(
              "E0502", a.range,
              fmt::format("argument '{}' of skill '{}' must be {}, but this variable is {}", params[i].name.name,
                          inst.skill.name, params[i].type.resolved->spelling, a.value->type->spelling));
        }
      }
    }
  }

  void checkItems(ItemsDecl& items) {
    const Type* t = items.itemType.resolved;
    if (t == nullptr || t->isError()) return;
    if (t->kind != TypeKind::Item) {
      diags_.error("E0314", items.itemType.range, fmt::format("'{}' is not an item type", t->spelling));
      return;
    }
    std::set<std::string> entryNames;
    for (auto& e : items.entries) {
      if (!entryNames.insert(e.name.name).second) {
        diags_.error("E0202", e.name.range,
                     fmt::format("item '{}' appears twice in '{}'", e.name.name, items.name.name));
      }
      std::set<std::string> given;
      for (auto& f : e.fields) {
        const Type* vt = check(f.value.get());
        const Param* field = nullptr;
        for (const auto& p : t->itemDecl->fields) {
          if (p.name.name == f.name.name) field = &p;
        }
        if (field == nullptr) {
          std::vector<std::string> names;
          for (const auto& p : t->itemDecl->fields) names.push_back(p.name.name);
          Diagnostic& d =
              diags_.error("E0314", f.name.range, fmt::format("{} has no field '{}'", t->spelling, f.name.name));
          const std::string guess = closestMatch(f.name.name, names);
          if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
          continue;
        }
        if (!given.insert(f.name.name).second) {
          diags_.error("E0314", f.name.range, fmt::format("field '{}' is given twice", f.name.name));
          continue;
        }
        if (field->type.resolved && !assignable(field->type.resolved, vt)) {
          diags_.error("E0314", f.value->range,
                       fmt::format("field '{}' is {}, but this value is {}", f.name.name,
                                   field->type.resolved->spelling, vt->spelling));
        } else if (!isConstantExpr(*f.value, false)) {
          diags_.error("E0305", f.value->range, "item fields must be constants");
        }
      }
      for (const auto& p : t->itemDecl->fields) {
        if (!given.count(p.name.name)) {
          diags_.error("E0314", e.range, fmt::format("item '{}' does not give field '{}'", e.name.name, p.name.name));
        }
      }
    }
  }

  void checkRobot(RobotDecl& r) {
    bool sawDof = false;
    for (auto& f : r.fields) {
      const Type* t = check(f.value.get());
      if (f.name.name == "dof") {
        sawDof = true;
        if (t->kind != TypeKind::Int || f.value->kind != ExprKind::Number || f.value->number < 1 ||
            f.value->number > 64) {
          diags_.error("E0315", f.value->range, "'dof' must be a whole number from 1 to 64");
        } else {
          r.dof = static_cast<int>(f.value->number);
        }
      } else {
        diags_.error("E0315", f.name.range, fmt::format("robot has no field '{}'; robots take 'dof'", f.name.name));
      }
    }
    if (!sawDof) diags_.error("E0315", r.name.range, fmt::format("robot '{}' needs 'dof: N'", r.name.name));
  }

  void checkPersonal(PersonalDecl& g) {
    for (auto& f : g.factors) {
      for (auto& a : f.args) {
        if (a.value && a.value->kind == ExprKind::Name && a.value->ref.kind == RefKind::Unresolved) continue;
        check(a.value.get());
      }
    }
    for (auto& a : g.accepts) check(a.get());
    for (auto& f : g.fallbacks) check(f.get());
    for (auto& c : g.guards) expect(c.get(), types_.boolean(), "a generator's 'if' guard");
    for (auto& rule : g.learnRules) {
      // Binder types come from the event's parameters (arity is checked by check-generators).
      if (rule.eventRef.kind == RefKind::Feedback) {
        const auto& ev = static_cast<const FeedbackDecl&>(*rule.eventRef.decl);
        for (std::size_t i = 0; i < rule.binders.size() && i < ev.params.size(); ++i) {
          rule.binders[i]->type = ev.params[i].type.resolved ? ev.params[i].type.resolved : err();
        }
      }
      for (auto& b : rule.binders) {
        if (b->type == nullptr) b->type = err();
      }
      for (auto& label : rule.labels) check(label.value.get());
      if (rule.condition) expect(rule.condition.get(), types_.boolean(), "a learning rule's 'if' condition");
    }
  }

  void checkTop(Decl& d) {
    switch (d.kind) {
      case DeclKind::Robot:
        checkRobot(static_cast<RobotDecl&>(d));
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
      case DeclKind::Skill: {
        auto& s = static_cast<SkillDecl&>(d);
        for (auto& b : s.body) checkScopeStmt(*b);
        checkActions(s.actions);
        break;
      }
      case DeclKind::Task:
        checkTask(static_cast<TaskDecl&>(d));
        break;
      default:
        break;
    }
  }

  // --- recursion ----------------------------------------------------------------------------

  void collectCalls(const Expr* e, std::vector<const FuncDecl*>& out) {
    if (e == nullptr) return;
    if (e->kind == ExprKind::Call && e->ref.kind == RefKind::Function) {
      const auto* f = static_cast<const FuncDecl*>(e->ref.decl);
      if (!f->isExtern) out.push_back(f);
    }
    for (const auto& op : e->operands) collectCalls(op.get(), out);
    for (const auto& a : e->args) collectCalls(a.value.get(), out);
    if (e->binder) collectCalls(e->binder->set.get(), out);
  }

  void checkRecursion(const std::vector<std::unique_ptr<Module>>& modules) {
    // Depth-first search; a callee found on the stack closes a cycle, reported once at its caller.
    std::map<const FuncDecl*, int> state;  // 0 unvisited, 1 on the stack, 2 done
    std::function<void(const FuncDecl*)> visit = [&](const FuncDecl* f) {
      state[f] = 1;
      std::vector<const FuncDecl*> callees;
      collectCalls(f->body.get(), callees);
      for (const FuncDecl* c : callees) {
        if (state[c] == 1) {
          diags_.error("E0308", f->name.range, fmt::format("function '{}' is recursive", f->name.name))
              .note(fmt::format("it calls '{}'", c->name.name), c->name.range);
          break;
        }
        if (state[c] == 0) visit(c);
      }
      state[f] = 2;
    };
    for (const auto& m : modules) {
      for (const auto& d : m->decls) {
        if (d->kind != DeclKind::Function) continue;  // only then is the downcast valid
        const auto* f = static_cast<const FuncDecl*>(d.get());
        if (!f->isExtern && state[f] == 0) visit(f);
      }
    }
  }

  TypeContext& types_;
  const GlobalSymbols& symbols_;
  DiagnosticEngine& diags_;
  bool inDomain_ = false;
  std::set<const ConstDecl*> constsInProgress_;
  std::set<const ConstDecl*> constCyclesReported_;
};

}  // namespace

bool checkTypes(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, const GlobalSymbols& symbols,
                DiagnosticEngine& diags) {
  const std::size_t before = diags.errorCount();
  Checker(types, symbols, diags).run(modules);
  return diags.errorCount() == before;
}

}  // namespace cbtl
