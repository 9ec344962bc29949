// check-types: declarations. Constants (checked on first use), index sets, variables with their domains and
// initial values, samples, the statements of a scope, item sets, robots and the expressions of generators.
#include "compiler/sema/TypeCheckerInternal.h"

#include "compiler/sema/TypeChecker.h"
#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace cbtl::detail {

namespace {

// The number of members of an index set when it is evident from the source (an enum, an item set, a
// list, or a range of integer literals); nullopt otherwise (lowering enumerates the rest).
std::optional<std::size_t> indexSetSize(const Expr* set) {
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

}  // namespace

void TypeChecker::checkIndex(IndexSpec* index) {
  if (index == nullptr || index->elementType != nullptr) return;
  const Type* set = check(index->set.get());
  index->elementType = elementOf(set, *index->set, "an index set");
  if (!index->elementType->isError() && !isConstantExpr(*index->set, false)) {
    diags_.error("E0305", index->set->range, "an index set must be known at compile time");
  }
}

// Constants are checked on first use, so a constant may be used before its declaration. One that is
// reached again while its own value is being checked is defined in terms of itself (E0316, reported once).
const Type* TypeChecker::constType(const Expr& use, const ConstDecl& c) {
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

void TypeChecker::checkConst(ConstDecl& c) {
  if (c.valueType != nullptr || constsInProgress_.count(&c)) return;
  constsInProgress_.insert(&c);
  checkConstValue(c);
  constsInProgress_.erase(&c);
}

void TypeChecker::checkConstValue(ConstDecl& c) {
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

void TypeChecker::checkDomain(VarDecl& v) {
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
  checkDomainForm(t, dt, d);
}

void TypeChecker::checkDomainForm(const Type* t, const Type* dt, const Expr* d) {
  auto bad = [&](const std::string& form) {
    diags_.error("E0304", d->range, fmt::format("the domain of a {} variable is written {}", t->spelling, form));
  };
  auto isRangeList = [&](std::size_t n) {
    return d->kind == ExprKind::List && d->operands.size() == n &&
           std::all_of(d->operands.begin(), d->operands.end(),
                       [](const ExprPtr& x) { return x->type && x->type->kind == TypeKind::Range; });
  };
  auto checkBox = [&](const std::vector<std::string>& names) { return checkBoxDomain(t, d, names); };
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

bool TypeChecker::checkBoxDomain(const Type* t, const Expr* d, const std::vector<std::string>& names) {
  if (d->kind != ExprKind::Call || d->ref.kind != RefKind::Builtin) return false;
  std::set<std::string> seen;
  for (const auto& a : d->args) {
    if (std::find(names.begin(), names.end(), a.name.name) == names.end() || !seen.insert(a.name.name).second) {
      diags_.error(
          "E0304", a.range,
          fmt::format("box(...) for {} takes named ranges {}", t->spelling, fmt::format("{}", fmt::join(names, ", "))));
      return true;
    }
    if (!a.value->type || a.value->type->kind != TypeKind::Range) {
      diags_.error("E0304", a.range, fmt::format("'{}' must be a range lo .. hi", a.name.name));
    }
  }
  return true;
}

void TypeChecker::checkVar(VarDecl& v) {
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
const Type* TypeChecker::sampleTarget(Expr* t) {
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

void TypeChecker::checkSample(SampleDecl& s) {
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

void TypeChecker::checkScopeStmt(Decl& d) {
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

void TypeChecker::checkItems(ItemsDecl& items) {
  const Type* t = items.itemType.resolved;
  if (t == nullptr || t->isError()) return;
  if (t->kind != TypeKind::Item) {
    diags_.error("E0314", items.itemType.range, fmt::format("'{}' is not an item type", t->spelling));
    return;
  }
  std::set<std::string> entryNames;
  for (auto& e : items.entries) {
    if (!entryNames.insert(e.name.name).second) {
      diags_.error("E0202", e.name.range, fmt::format("item '{}' appears twice in '{}'", e.name.name, items.name.name));
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
                     fmt::format("field '{}' is {}, but this value is {}", f.name.name, field->type.resolved->spelling,
                                 vt->spelling));
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

void TypeChecker::checkRobot(RobotDecl& r) {
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

void TypeChecker::checkPersonal(PersonalDecl& g) {
  for (auto& f : g.factors) {
    for (auto& a : f.args) {
      if (a.value && a.value->kind == ExprKind::Name && a.value->ref.kind == RefKind::Unresolved) continue;
      // A text model's context is a list of names of different types, each typed on its own.
      if (f.kind.name == "text" && a.name.name == "context" && a.value && a.value->kind == ExprKind::List) {
        for (auto& element : a.value->operands) check(element.get());
        continue;
      }
      check(a.value.get());
    }
  }
  for (auto& k : g.perKeys) {
    if (!(k.bareName() && k.expr->ref.kind == RefKind::Unresolved)) check(k.expr.get());  // else a capture
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

}  // namespace cbtl::detail
