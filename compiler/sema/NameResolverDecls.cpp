// resolve-names: declarations. Scope statements (var, require, sample, cost), callables with their
// parameters and bodies, personalized generators, skills with their action blocks, and tasks with their
// skill instances.
#include "compiler/sema/NameResolverInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <set>

namespace cbtl::detail {
namespace {

// Identifiers that only have meaning as model arguments (threshold direction, text scale and rating).
bool isModelKeyword(const std::string& name) {
  static const std::set<std::string> words = {"above", "below", "relative", "absolute", "digits", "options"};
  return words.count(name) > 0;
}

}  // namespace

void NameResolver::resolveIndex(IndexSpec* index) {
  if (index == nullptr) return;
  resolveExpr(index->set.get());
}

void NameResolver::resolveScopeStmt(Decl& d) {
  switch (d.kind) {
    case DeclKind::Var: {
      auto& v = static_cast<VarDecl&>(d);
      resolveIndex(v.index.get());
      resolveType(v.type);
      resolveExpr(v.domain.get());
      resolveExpr(v.init.get());
      break;
    }
    case DeclKind::Require:
      resolveExpr(static_cast<RequireDecl&>(d).condition.get());
      break;
    case DeclKind::Sample: {
      auto& s = static_cast<SampleDecl&>(d);
      push();
      if (s.forBinder) resolveBinder(*s.forBinder);
      for (auto& t : s.targets) resolveExpr(t.get());
      resolveArgs(s.args);
      s.samplerRef = lookup(s.sampler.name, s.sampler.range);
      if (s.samplerRef.kind != RefKind::Unresolved && s.samplerRef.kind != RefKind::Sampler &&
          !(s.samplerRef.kind == RefKind::Builtin && s.samplerRef.index == static_cast<int>(BuiltinId::Uniform))) {
        diags_.error("E0310", s.sampler.range, fmt::format("'{}' is not a sampler", s.sampler.name))
            .help("use 'uniform' or a name declared with 'extern sampler'");
      }
      pop();
      break;
    }
    case DeclKind::Cost:
      resolveExpr(static_cast<CostDecl&>(d).value.get());
      break;
    default:
      break;
  }
}

// Variables of a skill or task body are visible in the whole body (declaration order does not matter).
void NameResolver::bindBodyVariables(const std::vector<std::unique_ptr<Decl>>& body) {
  for (const auto& d : body) {
    if (d->kind == DeclKind::Var) {
      if (symbols_.values.count(d->name.name) && symbols_.values.at(d->name.name).kind == RefKind::Variable) {
        diags_
            .error("E0202", d->name.range,
                   fmt::format("'{}' is already a top-level variable, shared by every task", d->name.name))
            .note("declared here", symbols_.values.at(d->name.name).range);
        continue;
      }
      bindLocal(d->name, Symbol{RefKind::Variable, d.get(), -1, d->name.range});
    }
  }
}

void NameResolver::resolveActions(std::vector<std::unique_ptr<ActionStmt>>& stmts) {
  for (auto& s : stmts) {
    switch (s->kind) {
      case ActionStmtKind::Call: {
        s->calleeRef = lookup(s->callee.name, s->callee.range, false);
        if (s->calleeRef.kind != RefKind::Action) {
          Diagnostic& d = diags_.error("E0503", s->callee.range, fmt::format("'{}' is not an action", s->callee.name));
          std::vector<std::string> actions;
          for (const auto& [n, sym] : symbols_.values) {
            if (sym.kind == RefKind::Action) actions.push_back(n);
          }
          const std::string guess = closestMatch(s->callee.name, actions);
          if (!guess.empty())
            d.help(fmt::format("did you mean '{}'?", guess));
          else
            d.help("declare it with 'extern action NAME(...);' or import std.actions");
          s->calleeRef = NameRef{};
        }
        resolveArgs(s->args);
        break;
      }
      case ActionStmtKind::For:
        push();
        resolveBinder(*s->forBinder);
        resolveActions(s->body);
        pop();
        break;
      case ActionStmtKind::If:
        resolveExpr(s->condition.get());
        resolveActions(s->body);
        resolveActions(s->elseBody);
        break;
      case ActionStmtKind::Block:
        resolveActions(s->body);
        break;
      case ActionStmtKind::Allow:
        resolveAllowTarget(*s->allow);
        resolveActions(s->body);
        break;
    }
  }
}

// A bare name that names a declared clearance is that class, whatever else is in scope; anything else is a text
// expression. An unknown bare name gets its suggestion from the clearances as well as the values in scope.
void NameResolver::resolveAllowTarget(AllowClause& a) {
  Expr* target = a.target.get();
  if (target == nullptr) return;
  if (target->kind != ExprKind::Name) {
    resolveExpr(target);
    return;
  }
  if (auto it = symbols_.clearances.find(target->text); it != symbols_.clearances.end()) {
    a.clearance = it->second;
    return;
  }
  target->ref = lookup(target->text, target->range, false);
  if (target->ref.kind != RefKind::Unresolved || target->text.empty()) return;
  Diagnostic& d = diags_.error("E0201", target->range, fmt::format("unknown clearance or name '{}'", target->text));
  std::vector<std::string> names;
  for (const auto& [n, c] : symbols_.clearances) names.push_back(n);
  for (auto& n : visibleNames()) names.push_back(n);
  const std::string guess = closestMatch(target->text, names);
  if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
  d.note("an allow target is a declared clearance or a text naming a scene body or geom");
}

void NameResolver::resolveCallable(CallableDecl& c) {
  typeParams_.clear();
  for (const auto& tp : c.typeParams) typeParams_.push_back(tp.name);
  for (auto& p : c.params) resolveType(p.type);
  if (c.result) resolveType(*c.result);
  typeParams_.clear();
  if (c.kind == DeclKind::Function && !c.isExtern && !c.body) {
    diags_.error("E0315", c.name.range,
                 fmt::format("function '{}' needs a body ('= expression') or 'extern'", c.name.name));
  }
  if (c.kind == DeclKind::Function && c.isExtern && c.body) {
    diags_.error("E0315", c.body->range, "an extern function is implemented in C++ and cannot have a body");
  }
  if (!c.typeParams.empty() && !c.isExtern) {
    diags_.error("E0309", c.typeParams.front().range, "only extern declarations may have type parameters");
  }
  if (c.body) {
    push();
    for (std::size_t i = 0; i < c.params.size(); ++i) {
      bindLocal(c.params[i].name, Symbol{RefKind::Param, &c, static_cast<int>(i), c.params[i].name.range});
    }
    resolveExpr(c.body.get());
    pop();
  }
}

void NameResolver::resolvePersonal(PersonalDecl& g) {
  for (auto& p : g.params) resolveType(p.type);
  push();
  for (std::size_t i = 0; i < g.params.size(); ++i) {
    bindLocal(g.params[i].name, Symbol{RefKind::Param, &g, static_cast<int>(i), g.params[i].name.range});
  }
  for (auto& f : g.factors) resolveModelArgs(f);
  for (auto& k : g.perKeys) {
    // A bare name may be a capture of the 'when' patterns, which is no symbol: it is looked up quietly, and the
    // generator checker reports a name that is neither (E0412).
    if (k.bareName())
      k.expr->ref = lookupWithBinders(k.expr->text, k.expr->range, /*report=*/false);
    else
      resolveExpr(k.expr.get());
  }
  for (auto& a : g.accepts) resolveExpr(a.get());
  for (auto& f : g.fallbacks) resolveExpr(f.get());
  for (auto& c : g.guards) resolveExpr(c.get());
  for (auto& rule : g.learnRules) resolveLearnRule(rule);
  pop();
}

void NameResolver::resolveModelArgs(ModelFactor& f) {
  std::size_t positional = 0;
  for (auto& a : f.args) {
    // Model keywords (below, relative, ...) are interpreted by the generator checker, and so is any bare
    // word where a keyword belongs (a threshold's direction, a text model's scale and rating), so that a
    // wrong word is reported as a wrong model argument (E0406) rather than as an unknown name.
    const bool bareWord = a.value && a.value->kind == ExprKind::Name;
    const bool keywordPosition = (f.kind.name == "threshold" && a.name.name.empty() && positional == 2) ||
                                 (f.kind.name == "text" && (a.name.name == "scale" || a.name.name == "rating"));
    if (a.name.name.empty()) ++positional;
    if (bareWord && (isModelKeyword(a.value->text) || keywordPosition)) continue;
    resolveExpr(a.value.get());
  }
}

// A learning rule's event, then its labels and condition with the rule's binders in scope.
void NameResolver::resolveLearnRule(LearnRule& rule) {
  rule.eventRef = lookup(rule.event.name, rule.event.range, false);
  if (rule.eventRef.kind != RefKind::Feedback) {
    Diagnostic& d =
        diags_.error("E0210", rule.event.range, fmt::format("'{}' is not a declared feedback event", rule.event.name));
    std::vector<std::string> events;
    for (const auto& [n, sym] : symbols_.values) {
      if (sym.kind == RefKind::Feedback) events.push_back(n);
    }
    const std::string guess = closestMatch(rule.event.name, events);
    if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
    rule.eventRef = NameRef{};
  }
  // Binders shadow parameters on purpose: a binder named like a parameter binds it.
  push();
  for (auto& b : rule.binders) {
    if (b->name.name.empty()) continue;
    Symbol sym{RefKind::Binder, nullptr, -1, b->name.range};
    sym.binder = b.get();
    bindLocal(b->name, sym);
  }
  for (auto& label : rule.labels) resolveExpr(label.value.get());
  resolveExpr(rule.condition.get());
  pop();
}

void NameResolver::resolveSkill(SkillDecl& s) {
  for (auto& p : s.params) resolveType(p.type);
  push();
  for (std::size_t i = 0; i < s.params.size(); ++i) {
    bindLocal(s.params[i].name, Symbol{RefKind::Param, &s, static_cast<int>(i), s.params[i].name.range});
  }
  bindBodyVariables(s.body);
  for (auto& d : s.body) resolveScopeStmt(*d);
  resolveActions(s.actions);
  pop();
}

void NameResolver::resolveTask(TaskDecl& t) {
  push();
  bindBodyVariables(t.body);
  for (auto& d : t.body) resolveScopeStmt(*d);
  for (auto& inst : t.instances) {
    auto it = symbols_.skills.find(inst.skill.name);
    if (it == symbols_.skills.end()) {
      Diagnostic& d = diags_.error("E0209", inst.skill.range, fmt::format("unknown skill '{}'", inst.skill.name));
      std::vector<std::string> names;
      for (const auto& [n, decl] : symbols_.skills) names.push_back(n);
      const std::string guess = closestMatch(inst.skill.name, names);
      if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
    } else {
      inst.skillDecl = it->second;
    }
    resolveArgs(inst.args);
  }
  pop();
}

}  // namespace cbtl::detail
