// lower: top-level declarations and variables. Declarations that the graph lists by name (robots, enums,
// item types and sets, constants, observations, feedback events, functions, skills) are copied as they
// are; a variable becomes one graph variable per member of its family, each with its lowered domain.
#include "compiler/lower/LoweringInternal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cbtl::detail {

void Lowerer::declareTop(const Decl& d) {
  switch (d.kind) {
    case DeclKind::Robot:
      g_.robots.push_back({d.name.name, static_cast<const RobotDecl&>(d).dof});
      break;
    case DeclKind::Clearance: {
      const auto& c = static_cast<const ClearanceDecl&>(d);
      g_.clearances.push_back({c.name.name, c.bodies, metres(c.distance), span(d.range)});
      break;
    }
    case DeclKind::Enum: {
      ir::Enum e{d.name.name, {}, span(d.range)};
      for (const auto& m : static_cast<const EnumDecl&>(d).members) e.members.push_back(m.name);
      g_.enums.push_back(std::move(e));
      break;
    }
    case DeclKind::ItemType: {
      ir::ItemType t{d.name.name, {}, span(d.range)};
      for (const auto& f : static_cast<const ItemTypeDecl&>(d).fields)
        t.fields.push_back({f.name.name, typeDesc(f.type.resolved)});
      g_.itemTypes.push_back(std::move(t));
      break;
    }
    case DeclKind::ItemSet:
      declareItemSet(static_cast<const ItemsDecl&>(d));
      break;
    case DeclKind::Const: {
      const auto& c = static_cast<const ConstDecl&>(d);
      Ctx none;
      ir::Constant k{c.name.name, typeDesc(c.valueType), c.index ? c.index->elementType->spelling : "",
                     lower(c.value.get(), none), span(d.range)};
      g_.constants.push_back(std::move(k));
      break;
    }
    case DeclKind::Observe: {
      const auto& o = static_cast<const ObserveDecl&>(d);
      Ctx none;
      ir::Observation obs{o.name.name, typeDesc(o.type.resolved), std::nullopt, span(d.range)};
      if (o.index) obs.indexSet = lower(o.index->set.get(), none);
      g_.observations.push_back(std::move(obs));
      break;
    }
    case DeclKind::Feedback: {
      ir::Function f;
      f.name = d.name.name;
      f.kind = ir::FunctionKind::Feedback;
      for (const auto& p : static_cast<const FeedbackDecl&>(d).params)
        f.params.push_back({p.name.name, typeDesc(p.type.resolved)});
      f.span = span(d.range);
      g_.feedback.push_back(std::move(f));
      break;
    }
    case DeclKind::Function:
    case DeclKind::Sampler:
    case DeclKind::Action:
      declareCallable(static_cast<const CallableDecl&>(d));
      break;
    case DeclKind::Skill:
      g_.skills.push_back(d.name.name);
      break;
    default:
      break;
  }
}

double Lowerer::metres(const Length& l) {
  const double perUnit = l.unit.name == "mm" ? 0.001 : l.unit.name == "cm" ? 0.01 : 1.0;
  // + 0.0: a written "-0 mm" is refused by check-types, but no distance is ever the negative zero.
  return l.value * perUnit + 0.0;
}

void Lowerer::declareItemSet(const ItemsDecl& items) {
  ir::ItemSet s{items.name.name, items.itemType.name.name, {}, span(items.range)};
  Ctx none;
  for (const auto& entry : items.entries) {
    ir::ItemEntry e{entry.name.name, {}};
    for (const auto& f : entry.fields) e.fields.emplace_back(f.name.name, lower(f.value.get(), none));
    s.entries.push_back(std::move(e));
  }
  g_.itemSets.push_back(std::move(s));
}

void Lowerer::declareCallable(const CallableDecl& c) {
  ir::Function f;
  f.name = c.name.name;
  f.kind = c.kind == DeclKind::Function  ? ir::FunctionKind::Function
           : c.kind == DeclKind::Sampler ? ir::FunctionKind::Sampler
                                         : ir::FunctionKind::Action;
  f.isExtern = c.isExtern;
  for (const auto& tp : c.typeParams) f.typeParams.push_back(tp.name);
  for (const auto& p : c.params) f.params.push_back({p.name.name, typeDesc(p.type.resolved)});
  f.result = c.result ? typeDesc(c.result->resolved) : ir::TypeDesc{ir::TypeKind::Void, "void"};
  // The body is lowered once the global variables exist (lowerFunctionBodies): it may read them.
  if (c.body) pendingBodies_.emplace_back(g_.functions.size(), &c);
  if (c.kind == DeclKind::Function) inlinedNodes_[c.name.name] = static_cast<const FuncDecl&>(c).inlinedNodes;
  f.span = span(c.range);
  g_.functions.push_back(std::move(f));
}

void Lowerer::lowerFunctionBodies() {
  for (const auto& [index, decl] : pendingBodies_) {
    Ctx none;
    g_.functions[index].body = lower(decl->body.get(), none);
  }
  pendingBodies_.clear();
}

void Lowerer::lowerVar(const VarDecl& v, Ctx& ctx, std::vector<ir::VarId>& out) {
  std::vector<std::pair<std::string, std::optional<CVal>>> members;
  if (!familyMembers(v, ctx, members)) return;
  bool firstMember = true;
  for (const auto& [member, val] : members) {
    ir::Variable var;
    var.id = static_cast<ir::VarId>(g_.variables.size());
    var.name = ctx.prefix + v.name.name + (member.empty() ? "" : "[" + member + "]");
    var.type = typeDesc(v.type.resolved);
    // Domains and initial values read only constants and observations (checked by check-types), so
    // they are lowered in an empty context rather than a copy of one that grows with every variable.
    Ctx inner;
    inner.scope = ctx.scope;
    inner.prefix = ctx.prefix;
    var.domain = lowerDomain(v, inner);
    if (firstMember) reportEmptyRange(v, var.domain);  // once per declaration, not per member
    firstMember = false;
    if (v.init) var.init = lower(v.init.get(), inner);
    std::size_t units = 1 + (var.init ? nodeCount(*var.init) : 0) + (var.domain.set ? nodeCount(*var.domain.set) : 0);
    for (const auto& b : var.domain.bounds) units += (b.lo ? nodeCount(*b.lo) : 0) + (b.hi ? nodeCount(*b.hi) : 0);
    if (!grow(units, v.range)) return;
    if (!member.empty()) {
      var.family = ctx.prefix + v.name.name;
      var.indexText = member;
    }
    var.scope = ctx.scope;
    var.span = span(v.range);
    ctx.vars[&v][member] = var.id;
    out.push_back(var.id);
    g_.variables.push_back(std::move(var));
    declOf_.push_back(&v);
  }
}

bool Lowerer::familyMembers(const VarDecl& v, const Ctx& ctx,
                            std::vector<std::pair<std::string, std::optional<CVal>>>& members) {
  if (!v.index) {
    members.emplace_back("", std::nullopt);
    return true;
  }
  bool tooLarge = false;
  auto values = enumerate(v.index->set.get(), ctx, &tooLarge);
  if (!values && tooLarge) {
    tooManyMembers(v.index->set->range, "a variable family");
    return false;
  }
  if (!values) {
    diags_.error("E0305", v.index->set->range, "the index set of a variable family must be known at compile time");
    return false;
  }
  if (values->empty()) {  // nothing to declare: a sampler of the family would write no variable
    diags_.error("E0311", v.index->set->range,
                 fmt::format("the index set of the family '{}' is empty, so it declares no variable", v.name.name));
    return false;
  }
  std::set<std::string> seen;
  for (const auto& val : *values) {
    if (!seen.insert(val.text).second) {
      diags_.error("E0202", v.index->set->range,
                   fmt::format("'{}[{}]' is declared twice: the index set lists {} more than once", v.name.name,
                               val.text, val.text));
      return false;
    }
    members.emplace_back(val.text, val);
  }
  return true;
}

ir::Domain Lowerer::lowerDomain(const VarDecl& v, Ctx& ctx) {
  ir::Domain d;
  const Expr* e = v.domain.get();
  if (e == nullptr) return d;
  if (e->kind == ExprKind::Range) {
    d.bounds.push_back({lower(e->operands[0].get(), ctx), lower(e->operands[1].get(), ctx)});
  } else if (e->kind == ExprKind::Call) {  // box(x:, y:, yaw:/z:)
    const Type* t = v.type.resolved;
    std::vector<std::string> order =
        t->kind == TypeKind::SE2 ? std::vector<std::string>{"x", "y", "yaw"} : std::vector<std::string>{"x", "y", "z"};
    if (t->kind == TypeKind::Vec) order.resize(static_cast<std::size_t>(std::min(3, t->size)));
    for (const auto& name : order) {
      ir::Bound b;
      for (const auto& a : e->args) {
        if (a.name.name == name && a.value->kind == ExprKind::Range) {
          b.lo = lower(a.value->operands[0].get(), ctx);
          b.hi = lower(a.value->operands[1].get(), ctx);
        }
      }
      d.bounds.push_back(std::move(b));
    }
  } else if (e->kind == ExprKind::List && v.type.resolved->kind == TypeKind::Vec) {
    for (const auto& r : e->operands) {
      d.bounds.push_back({lower(r->operands[0].get(), ctx), lower(r->operands[1].get(), ctx)});
    }
  } else {
    d.set = lower(e, ctx);
  }
  return d;
}

// The value of a bound made of numbers, constants and arithmetic (nothing observed), or none.
std::optional<double> Lowerer::foldedNumber(const ir::Expr& e, int depth) const {
  if (depth > 64) return std::nullopt;
  if (e.op == ir::Op::Num) return e.number;
  if (e.op == ir::Op::Const && e.children.empty()) {
    for (const auto& c : g_.constants) {
      if (c.name == e.text && c.indexSet.empty()) return foldedNumber(c.value, depth + 1);
    }
    return std::nullopt;
  }
  std::vector<double> x;
  for (const auto& child : e.children) {
    const auto v = foldedNumber(child, depth + 1);
    if (!v) return std::nullopt;
    x.push_back(*v);
  }
  if (e.op == ir::Op::Neg && x.size() == 1) return -x[0];
  if (x.size() != 2) return std::nullopt;
  if (e.op == ir::Op::Add) return x[0] + x[1];
  if (e.op == ir::Op::Sub) return x[0] - x[1];
  if (e.op == ir::Op::Mul) return x[0] * x[1];
  if (e.op == ir::Op::Div) return x[0] / x[1];
  return std::nullopt;
}

void Lowerer::reportEmptyRange(const VarDecl& v, const ir::Domain& d) {
  // A constant bound that is not a finite number (0.0 / 0.0, 1.0 / 0.0) leaves nothing to sample from and no
  // value the re-check would accept: `cbtl` refused every solution as a bug.
  for (const auto& b : d.bounds) {
    for (const auto* bound : {&b.lo, &b.hi}) {
      if (!*bound) continue;
      if (const auto value = foldedNumber(**bound); value && !std::isfinite(*value)) {
        diags_.error("E0304", v.domain->range,
                     fmt::format("the domain of '{}' has a bound that is not a finite number ({})", v.name.name,
                                 std::isnan(*value) ? "NaN"
                                 : *value > 0       ? "infinity"
                                                    : "-infinity"));
        return;
      }
    }
  }
  for (const auto& b : d.bounds) {
    if (b.lo && b.hi && b.lo->op == ir::Op::Num && b.hi->op == ir::Op::Num && b.lo->number > b.hi->number) {
      diags_.error("E0311", v.domain->range,
                   fmt::format("the domain of '{}' is empty: {} > {}", v.name.name, b.lo->number, b.hi->number));
    }
  }
}

}  // namespace cbtl::detail
