// lower: the body of a scope (the global scope, a task, a skill instance). Its variables come first so
// that every statement can name them; then the domain constraints the samplers cannot keep, and the
// `require`, `sample` and `cost` statements in source order, each recording its hyperedge.
#include "compiler/lower/LoweringInternal.h"

#include <fmt/format.h>

#include <algorithm>

namespace cbtl::detail {
namespace {

bool readsObservation(const ir::Expr& e) {
  if (e.op == ir::Op::Obs) return true;
  for (const auto& c : e.children)
    if (readsObservation(c)) return true;
  return false;
}

// `var in set` or, with a field, `var.field in set` (set: a range or a set expression).
ir::Expr domainTest(const ir::Variable& var, const std::optional<std::string>& field, ir::Expr set) {
  ir::Expr ref;
  ref.op = ir::Op::Var;
  ref.type = var.type;
  ref.text = var.name;
  ref.id = static_cast<std::int64_t>(var.id);
  if (field) {
    ir::Expr member;
    member.op = ir::Op::Member;
    member.type.kind = ir::TypeKind::Real;
    member.type.spelling = "real";
    member.text = *field;
    member.children.push_back(std::move(ref));
    ref = std::move(member);
  }
  ir::Expr in;
  in.op = ir::Op::In;
  in.type.kind = ir::TypeKind::Bool;
  in.type.spelling = "bool";
  in.children.push_back(std::move(ref));
  in.children.push_back(std::move(set));
  return in;
}

// The conjunction of a range test per two-sided bound of `var` (per field of a vector or pose), if any.
std::optional<ir::Expr> boundsTest(const ir::Variable& var) {
  static const std::vector<std::string> kVec = {"x", "y", "z"}, kSe2 = {"x", "y", "yaw"};
  const std::vector<std::string>& fields = var.type.kind == ir::TypeKind::SE2 ? kSe2 : kVec;
  std::optional<ir::Expr> cond;
  for (std::size_t c = 0; c < var.domain.bounds.size(); ++c) {
    const ir::Bound& b = var.domain.bounds[c];
    if (!b.lo || !b.hi) continue;  // a one-sided bound cannot be written as a range test
    if (var.domain.bounds.size() > 1 && c >= fields.size()) break;
    ir::Expr range;
    range.op = ir::Op::Range;
    range.type.kind = ir::TypeKind::Range;
    range.type.spelling = "range";
    range.children = {*b.lo, *b.hi};
    std::optional<std::string> field;
    if (var.domain.bounds.size() > 1) field = fields[c];
    ir::Expr test = domainTest(var, field, std::move(range));
    if (!cond) {
      cond = std::move(test);
    } else {
      ir::Expr both;
      both.op = ir::Op::And;
      both.type = test.type;
      both.children.push_back(std::move(*cond));
      both.children.push_back(std::move(test));
      cond = std::move(both);
    }
  }
  return cond;
}

// Domains the solver's samplers alone cannot keep become constraints named `<var>.domain`, which a graph
// dump shows and the solver checks like any other: a domain read from an observation (`var book : Book
// in pickable`) changes from one CSP to the next, and an initial value read from an observation
// (`= plateXY`) may lie outside the declared domain, while the solver tries the initial values first.
std::optional<ir::Expr> domainConstraint(const ir::Variable& var) {
  const bool observedSet = var.domain.set && var.domain.set->op == ir::Op::Obs;
  const bool observedInit = var.init && readsObservation(*var.init);
  if (observedSet || (observedInit && var.domain.set)) return domainTest(var, std::nullopt, *var.domain.set);
  if (observedInit && !var.domain.bounds.empty()) return boundsTest(var);
  return std::nullopt;
}

}  // namespace

void Lowerer::lowerBody(const std::vector<const Decl*>& body, Ctx& ctx, std::vector<ir::VarId>& vars,
                        std::vector<std::uint32_t>& constraints, std::vector<std::uint32_t>& samplers,
                        std::vector<std::uint32_t>& costs) {
  const std::size_t firstVar = vars.size();
  for (const Decl* d : body) {
    if (d->kind == DeclKind::Var) lowerVar(static_cast<const VarDecl&>(*d), ctx, vars);
  }
  for (std::size_t i = firstVar; i < vars.size(); ++i) {
    const ir::Variable& var = g_.variables[vars[i]];
    std::optional<ir::Expr> cond = domainConstraint(var);
    if (!cond) continue;
    constraints.push_back(addConstraint(var.name + ".domain", std::move(*cond), var.scope, declOf_[var.id]->range));
  }
  std::size_t anonymous = 0;
  for (const Decl* d : body) {
    if (d->kind == DeclKind::Require) {
      const auto& r = static_cast<const RequireDecl&>(*d);
      const std::string base =
          ctx.prefix + (r.name.name.empty() ? fmt::format("require#{}", ++anonymous) : r.name.name);
      lowerRequire(r, ctx, constraints, base, r.condition.get(), "");
    } else if (d->kind == DeclKind::Sample) {
      lowerSample(static_cast<const SampleDecl&>(*d), ctx, samplers);
    } else if (d->kind == DeclKind::Cost) {
      lowerCost(static_cast<const CostDecl&>(*d), ctx, costs);
    }
  }
}

std::uint32_t Lowerer::addConstraint(std::string name, ir::Expr expr, const std::string& scope, SourceRange at) {
  grow(1 + nodeCount(expr), at);
  ir::Constraint c;
  c.id = static_cast<std::uint32_t>(g_.constraints.size());
  c.name = std::move(name);
  std::set<ir::VarId> vars;
  collectVars(expr, vars);
  c.vars.assign(vars.begin(), vars.end());
  c.expr = std::move(expr);
  c.scope = scope;
  c.span = span(at);
  g_.constraints.push_back(std::move(c));
  return g_.constraints.back().id;
}

void Lowerer::lowerRequire(const RequireDecl& r, Ctx& ctx, std::vector<std::uint32_t>& out, const std::string& base,
                           const Expr* cond, std::string suffix, std::size_t instances) {
  if (cond->kind == ExprKind::Quantifier && cond->quant == QuantKind::Forall && !cond->binder->names.empty() &&
      unrollForall(r, ctx, out, base, *cond, suffix, instances)) {
    return;
  }
  out.push_back(addConstraint(base + suffix, lower(cond, ctx), ctx.scope, r.range));
}

// Binder values are set in ctx.env for the body and removed again, so no context is copied per binding.
bool Lowerer::unrollForall(const RequireDecl& r, Ctx& ctx, std::vector<std::uint32_t>& out, const std::string& base,
                           const Expr& cond, const std::string& suffix, std::size_t instances) {
  auto values = enumerate(cond.binder->set.get(), ctx);
  const auto& names = cond.binder->names;
  std::size_t total = instances;
  for (std::size_t i = 0; values && i < names.size() && total <= kMaxUnrolled; ++i)
    total *= std::max<std::size_t>(1, values->size());
  if (!values || total > kMaxUnrolled) return false;
  if (values->empty()) return true;  // vacuously true: no instance
  std::vector<std::size_t> pos(names.size(), 0);
  while (!tooLarge_) {
    std::string binding;
    for (std::size_t i = 0; i < names.size(); ++i) {
      ctx.env[names[i].get()] = (*values)[pos[i]];
      binding += (i ? "," : "") + (*values)[pos[i]].text;
    }
    const Expr* where = cond.operands[0].get();
    auto decided = decide(where, ctx);
    if (!decided || *decided) {
      const std::string s = suffix + "[" + binding + "]";
      if (decided) {
        lowerRequire(r, ctx, out, base, cond.operands[1].get(), s, total);
      } else {
        // A `where` that reads more than the binders is left to the runtime: the instance implies it.
        ir::Expr imp;
        imp.op = ir::Op::Implies;
        imp.type = {ir::TypeKind::Bool, "bool"};
        imp.children.push_back(lower(where, ctx));
        imp.children.push_back(lower(cond.operands[1].get(), ctx));
        out.push_back(addConstraint(base + s, std::move(imp), ctx.scope, r.range));
      }
    }
    // Next binding: the last binder varies fastest.
    std::size_t k = names.size();
    while (k > 0 && ++pos[k - 1] == values->size()) pos[--k] = 0;
    if (k == 0) break;
  }
  for (const auto& n : names) ctx.env.erase(n.get());
  return true;
}

void Lowerer::lowerSample(const SampleDecl& s, Ctx& ctx, std::vector<std::uint32_t>& out) {
  if (!s.forBinder) {
    lowerSampleInstance(s, ctx, out);
    return;
  }
  bool tooLarge = false;
  auto values = enumerate(s.forBinder->set.get(), ctx, &tooLarge);
  if (!values && tooLarge) {
    tooManyMembers(s.forBinder->set->range, "the 'for' set of a sample statement");
    return;
  }
  if (!values) {
    diags_.error("E0305", s.forBinder->set->range, "the 'for' set of a sample statement must be known at compile time");
    return;
  }
  // One sampler per member; the binder's value is set in ctx.env for each and removed afterwards.
  for (const auto& v : *values) {
    if (tooLarge_) break;
    for (const auto& n : s.forBinder->names) ctx.env[n.get()] = v;
    lowerSampleInstance(s, ctx, out);
  }
  for (const auto& n : s.forBinder->names) ctx.env.erase(n.get());
}

void Lowerer::lowerSampleInstance(const SampleDecl& s, Ctx& inner, std::vector<std::uint32_t>& out) {
  ir::Sampler smp;
  smp.id = static_cast<std::uint32_t>(g_.samplers.size());
  smp.sampler = s.sampler.name;
  std::set<ir::VarId> writes, reads;
  for (const auto& t : s.targets) {
    // A variable named without an index writes all its members (a scalar's one).
    if (t->kind == ExprKind::Name && t->ref.kind == RefKind::Variable) {
      for (const auto& [m, id] : lookupVars(t->ref.decl, inner)) writes.insert(id);
    } else {
      collectVars(lower(t.get(), inner), writes);
    }
  }
  const auto* callee =
      s.samplerRef.kind == RefKind::Sampler ? static_cast<const CallableDecl*>(s.samplerRef.decl) : nullptr;
  std::size_t units = 1;
  for (const auto* a : orderedArgs(callee, s.args)) {
    smp.args.push_back(lower(a->value.get(), inner));
    collectVars(smp.args.back(), reads);
    units += nodeCount(smp.args.back());
  }
  if (!grow(units, s.range)) return;
  if (smp.sampler == "uniform") checkUniformBounds(s, writes);
  smp.writes.assign(writes.begin(), writes.end());
  smp.reads.assign(reads.begin(), reads.end());
  smp.scope = inner.scope;
  smp.span = span(s.range);
  out.push_back(smp.id);
  g_.samplers.push_back(std::move(smp));
}

// `uniform` draws a number between its variable's bounds, so a number-valued variable needs both bounds on every
// component (Conf takes its robot's joint limits). The runtime refuses it too, but only at load and without a
// caret; here it is reported once per declaration, where the sample statement is.
void Lowerer::checkUniformBounds(const SampleDecl& s, const std::set<ir::VarId>& writes) {
  std::set<const VarDecl*> reported;
  for (ir::VarId id : writes) {
    const ir::Variable& v = g_.variables[id];
    const ir::TypeKind k = v.type.kind;
    if (k != ir::TypeKind::Real && k != ir::TypeKind::Int && k != ir::TypeKind::Vec && k != ir::TypeKind::SE2 &&
        k != ir::TypeKind::SE3)
      continue;
    if (v.domain.set) continue;
    bool bounded = !v.domain.bounds.empty();
    for (const auto& b : v.domain.bounds) bounded = bounded && b.lo && b.hi;
    const VarDecl* decl = id < declOf_.size() ? declOf_[id] : nullptr;
    if (bounded || !reported.insert(decl).second) continue;
    const bool scalar = k == ir::TypeKind::Real || k == ir::TypeKind::Int;
    const std::string name = v.family.empty() ? v.name : v.family;
    Diagnostic& d = diags_.error(
        "E0310", s.sampler.range,
        scalar ? fmt::format("'uniform' cannot draw '{}': it has no lower or no upper bound", name)
               : fmt::format("'uniform' cannot draw '{}': a component of its {} has no lower or no upper bound", name,
                             v.type.spelling));
    if (decl != nullptr) d.note("declared here", decl->name.range);
    d.help(scalar ? "bound it where it is declared, e.g. `in 0 .. 10`, or draw it with a sampler that takes bounds"
           : k == ir::TypeKind::Vec ? "bound every component where it is declared, e.g. `in [0 .. 1, 0 .. 1]`"
                                    : "bound its position where it is declared, e.g. `in box(x: 0 .. 1, ...)`");
  }
}

void Lowerer::lowerCost(const CostDecl& c, Ctx& ctx, std::vector<std::uint32_t>& out) {
  ir::Cost cost;
  cost.maximize = c.maximize;
  cost.expr = lower(c.value.get(), ctx);
  std::set<ir::VarId> vs;
  collectVars(cost.expr, vs);
  cost.vars.assign(vs.begin(), vs.end());
  cost.span = span(c.range);
  if (!grow(1 + nodeCount(cost.expr), c.range)) return;
  out.push_back(static_cast<std::uint32_t>(g_.costs.size()));
  g_.costs.push_back(std::move(cost));
}

}  // namespace cbtl::detail
