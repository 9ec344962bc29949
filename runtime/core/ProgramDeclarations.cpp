// ProgramCompiler's compilation of a graph's declarations: initial values, constraints, domain checks,
// samplers (with their `uniform` plans), generators (factors and learning rules) and costs. Each sets the
// location errors are reported at to the declaration it compiles, and clears it when done.
#include "runtime/core/ProgramCompiler.h"
#include "runtime/core/TextContext.h"

#include <fmt/format.h>

#include <algorithm>

namespace cbtl::rt {

namespace {

// A scope with no parameters and no binders, whose binders allocate from `top`.
ProgramCompiler::Scope topLevel(std::uint32_t& top) {
  ProgramCompiler::Scope scope;
  scope.frameTop = &top;
  return scope;
}

}  // namespace

std::vector<std::pair<ir::VarId, std::uint32_t>> ProgramCompiler::compileInitialValues() {
  std::vector<std::pair<ir::VarId, std::uint32_t>> inits;
  for (const auto& v : program_.graph().variables) {
    if (!v.init) continue;
    locateAt(&v.span);
    std::uint32_t top = 0;
    Scope scope = topLevel(top);
    inits.emplace_back(v.id, compile(*v.init, scope));
  }
  locateAt(nullptr);
  return inits;
}

std::vector<CompiledConstraint> ProgramCompiler::compileConstraints() {
  std::vector<CompiledConstraint> constraints;
  for (const auto& c : program_.graph().constraints) {
    locateAt(&c.span);
    std::uint32_t top = 0;
    Scope scope = topLevel(top);
    constraints.push_back(CompiledConstraint{&c, compile(c.expr, scope)});
  }
  locateAt(nullptr);
  return constraints;
}

std::vector<DomainCheck> ProgramCompiler::compileDomainChecks() {
  const auto& variables = program_.graph().variables;
  std::vector<DomainCheck> checks(variables.size());
  for (const auto& v : variables) {
    locateAt(&v.span);
    DomainCheck& check = checks[v.id];
    std::uint32_t top = 0;
    Scope scope = topLevel(top);
    for (const auto& b : v.domain.bounds) {
      check.lo.push_back(b.lo ? compile(*b.lo, scope) : UINT32_MAX);
      check.hi.push_back(b.hi ? compile(*b.hi, scope) : UINT32_MAX);
    }
    if (v.domain.set && v.domain.set->op != ir::Op::Obs) {
      ValueType elem;
      check.members = setMembers(*v.domain.set, elem, scope);
    }
  }
  locateAt(nullptr);
  return checks;
}

// Every member of an enum or item type, as a Choice.
UniformPlan ProgramCompiler::uniformPlanOfType(const ValueType& t, Scope& scope) {
  UniformPlan plan;
  plan.kind = UniformPlan::Kind::Choice;
  ir::Expr set;
  set.op = t.kind == ValueKind::Enum ? ir::Op::EnumSet : ir::Op::ItemSet;
  const ir::ItemSet* items = program_.findItemSetOfType(t.typeName);
  set.text = t.kind == ValueKind::Enum ? t.typeName : (items != nullptr ? items->name : t.typeName);
  ValueType elem;
  plan.choices = setMembers(set, elem, scope);
  return plan;
}

// How `sample v ~ uniform` draws v: from its declared set, every value of a finite type, or between its bounds.
UniformPlan ProgramCompiler::uniformPlan(const ir::Sampler& s, ir::VarId v, Scope& scope) {
  const auto& var = program_.graph().variables.at(v);
  const ValueType& t = program_.slot(v).type;
  UniformPlan plan;
  // An observed set draws from the members the observation lists (the variable's `.domain` constraint, added by
  // the compiler, still checks every value whatever sampler wrote it).
  if (var.domain.set && var.domain.set->op == ir::Op::Obs && var.domain.set->children.empty() &&
      (t.kind == ValueKind::Enum || t.kind == ValueKind::Item)) {
    plan = uniformPlanOfType(t, scope);
    plan.observedFlags = program_.observationOffset(var.domain.set->text);
  } else if (var.domain.set && var.domain.set->op != ir::Op::Obs) {
    ValueType elem;
    plan.kind = UniformPlan::Kind::Choice;
    plan.choices = setMembers(*var.domain.set, elem, scope);
  } else if (t.kind == ValueKind::Bool) {
    plan.kind = UniformPlan::Kind::Bool;
  } else if (t.kind == ValueKind::Enum || t.kind == ValueKind::Item) {
    plan = uniformPlanOfType(t, scope);
  } else if (t.kind == ValueKind::Real || t.kind == ValueKind::Int || t.kind == ValueKind::Vec ||
             t.kind == ValueKind::SE2 || t.kind == ValueKind::SE3 || t.kind == ValueKind::Conf) {
    plan.kind = t.kind == ValueKind::Int ? UniformPlan::Kind::Int : UniformPlan::Kind::Real;
    if (var.domain.bounds.size() != t.width) {
      throw RuntimeError(Program::where(s.span),
                         fmt::format("'uniform' needs bounds on every component of '{}'", var.name));
    }
    for (const auto& b : var.domain.bounds) {
      if (!b.lo || !b.hi)
        throw RuntimeError(Program::where(s.span), fmt::format("'uniform' needs '{}' to be bounded", var.name));
      plan.lo.push_back(compile(*b.lo, scope));
      plan.hi.push_back(compile(*b.hi, scope));
    }
  } else {
    throw RuntimeError(Program::where(s.span),
                       fmt::format("'uniform' cannot draw '{}' of type {}", var.name, var.type.spelling));
  }
  if (plan.kind == UniformPlan::Kind::Choice && plan.choices.empty()) {
    throw RuntimeError(Program::where(s.span), fmt::format("'{}' has an empty domain", var.name));
  }
  return plan;
}

std::vector<CompiledSampler> ProgramCompiler::compileSamplers() {
  std::vector<CompiledSampler> samplers;
  for (const auto& s : program_.graph().samplers) {
    locateAt(&s.span);
    CompiledSampler cs;
    cs.source = &s;
    cs.writes = s.writes;
    std::uint32_t top = 0;
    Scope scope = topLevel(top);
    if (s.sampler == "uniform") {
      for (ir::VarId v : s.writes) cs.uniform.push_back(uniformPlan(s, v, scope));
    } else {
      cs.impl = program_.builtins().sampler(s.sampler);
      if (cs.impl == nullptr)
        throw RuntimeError(Program::where(s.span),
                           fmt::format("built-in sampler '{}' has no implementation in this runtime", s.sampler));
      for (const auto& a : s.args) {
        cs.args.push_back(compile(a, scope));
        cs.argWidths.push_back(program_.pool_.width(cs.args.back()));
        cs.argsWidth += cs.argWidths.back();
      }
    }
    for (ir::VarId v : cs.writes) cs.outWidth += program_.slot(v).type.width;
    samplers.push_back(std::move(cs));
  }
  locateAt(nullptr);
  return samplers;
}

// A learning rule against its frame: the event's arguments one after another, the generator parameters they
// bind read from there; labels (with the feature of the factor each labels) and the condition over that.
CompiledLearnRule ProgramCompiler::compileLearnRule(const ir::Generator& g, const ir::LearnRule& r) {
  locateAt(&r.span);
  const auto& feedback = program_.graph().feedback;
  CompiledLearnRule cr;
  cr.source = &r;
  bool found = false;
  for (std::size_t i = 0; i < feedback.size(); ++i) {
    if (feedback[i].name == r.event) {
      cr.eventIndex = static_cast<std::uint32_t>(i);
      found = true;
    }
  }
  if (!found) throw RuntimeError(Program::where(r.span), fmt::format("unknown feedback event '{}'", r.event));
  const auto& ev = feedback[cr.eventIndex];
  std::uint32_t top = 0;
  Scope scope = topLevel(top);
  scope.params.assign(g.params.size(), UINT32_MAX);
  for (std::size_t i = 0; i < r.binders.size() && i < ev.params.size(); ++i) {
    const ValueType bt = program_.typeOf(ev.params[i].type);
    cr.binderTypes.push_back(bt);
    cr.binderFrame.push_back(top);
    if (r.binders[i] != "_") scope.locals[r.binders[i]] = top;
    for (std::size_t p = 0; p < g.params.size(); ++p) {
      if (i < r.binds.size() && r.binds[i] == g.params[p].name) {
        scope.params[p] =
            program_.pool_.add(Node{Op::ReadFrame, std::max<std::uint16_t>(bt.width, 1), top, 0, 0, nullptr, {}, {}});
      }
    }
    top += std::max<std::uint16_t>(bt.width, 1);
  }
  // What the rule evaluates on an event may read only the parameters the rule binds; `what` reads `names`.
  auto requireBound = [&](const std::vector<std::string>& names, const std::string& what) {
    for (const auto& pn : names) {
      for (std::size_t p = 0; p < g.params.size(); ++p) {
        if (g.params[p].name == pn && scope.params[p] == UINT32_MAX) {
          throw RuntimeError(
              Program::where(r.span),
              fmt::format("learning rule '{}' does not bind parameter '{}', which {} reads", r.event, pn, what));
        }
      }
    }
  };
  for (const auto& l : r.labels) {
    int factor = -1;
    for (std::size_t k = 0; k < g.factors.size(); ++k) {
      if (l.factor.empty() ? g.factors.size() == 1 : g.factors[k].label == l.factor) factor = static_cast<int>(k);
    }
    if (factor < 0) throw RuntimeError(Program::where(r.span), fmt::format("label names no factor of '{}'", g.name));
    const auto& f = g.factors[static_cast<std::size_t>(factor)];
    std::uint32_t featureNode = UINT32_MAX;
    for (const auto& entry : f.context) {
      requireBound(entry.params, fmt::format("the context of factor '{}'", f.label));
    }
    cr.contexts.push_back(compileContext(*this, program_, f, scope));
    if (f.feature) {
      requireBound(f.params, fmt::format("factor '{}'", f.label));
      featureNode = compile(*f.feature, scope);
    }
    cr.labels.push_back({factor, compile(l.value, scope)});
    cr.features.push_back(featureNode);
  }
  for (const auto& key : g.perKeys) {
    if (!key.expr) {  // a parameter or capture: the learner reads the binder that binds it
      cr.keys.push_back(UINT32_MAX);
      cr.keyTypes.emplace_back();
      continue;
    }
    requireBound(key.params, fmt::format("the key '{}'", key.name));
    cr.keys.push_back(compile(*key.expr, scope));
    cr.keyTypes.push_back(program_.typeOf(key.expr->type));
  }
  if (r.condition) cr.condition = compile(*r.condition, scope);
  cr.frameWidth = top;
  program_.frameSize_ = std::max<std::size_t>(program_.frameSize_, top);
  return cr;
}

std::vector<CompiledGenerator> ProgramCompiler::compileGenerators() {
  std::vector<CompiledGenerator> generators;
  for (const auto& g : program_.graph().generators) {
    locateAt(&g.span);
    CompiledGenerator cg;
    cg.source = &g;
    for (const auto& f : g.factors) cg.factors.push_back(CompiledFactor{&f});
    for (const auto& r : g.learnRules) cg.rules.push_back(compileLearnRule(g, r));
    for (const auto& p : g.params) cg.paramTypes.push_back(program_.typeOf(p.type));
    generators.push_back(std::move(cg));
  }
  locateAt(nullptr);
  return generators;
}

std::vector<std::uint32_t> ProgramCompiler::compileCosts() {
  std::vector<std::uint32_t> costs;
  for (const auto& c : program_.graph().costs) {
    std::uint32_t top = 0;
    Scope scope = topLevel(top);
    locateAt(&c.span);
    const std::uint32_t node = compile(c.expr, scope);
    costs.push_back(c.maximize ? program_.pool_.add(Node{Op::Neg, 1, 0, 0, 0, nullptr, {node}, {}}) : node);
  }
  locateAt(nullptr);
  return costs;
}

}  // namespace cbtl::rt
