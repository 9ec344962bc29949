// lower: personalized generators. A generator is kept whole in the graph (the runtime instantiates it
// per matching variable); its patterns, model factors, guards and learning rules are lowered as written,
// and W0401 warns about a parameter whose pattern matches no variable of any task.
#include "compiler/lower/LoweringInternal.h"

#include "compiler/sema/GeneratorChecker.h"
#include "ir/OpNames.h"
#include "ir/Pattern.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <regex>

namespace cbtl::detail {
namespace {

// A number literal, possibly negated: the generator checker accepts nothing else as a factor's range.
double constNumber(const Expr* e) {
  if (e == nullptr) return 0;
  if (e->kind == ExprKind::Unary && e->unaryOp == UnaryOp::Neg) return -constNumber(e->operands[0].get());
  return e->number;
}

}  // namespace

void Lowerer::lowerGenerator(const PersonalDecl& p) {
  ir::Generator g;
  g.name = p.name.name;
  g.span = span(p.range);
  for (const auto& prm : p.params) g.params.push_back({prm.name.name, typeDesc(prm.type.resolved)});
  for (const auto& pat : p.patterns) {
    g.patterns.push_back({pat.param.name, static_cast<std::uint32_t>(std::max(0, pat.paramIndex)),
                          pat.kind == PatternKind::Glob ? ir::PatternKind::Glob : ir::PatternKind::Regex, pat.pattern,
                          span(pat.patternRange)});
  }
  for (const auto& c : p.captures) g.captures.push_back(c.name);
  Ctx none;
  for (const auto& k : p.perKeys) {
    ir::PerKey key{k.spelling.name, std::nullopt, {}};
    if (perKeyKind(p, k) == PerKeyKind::Expression) {
      key.expr = lower(k.expr.get(), none);
      for (int pi : paramsRead(k.expr.get())) key.params.push_back(p.params[static_cast<std::size_t>(pi)].name.name);
    }
    g.perKeys.push_back(std::move(key));
  }
  for (const auto& f : p.factors) g.factors.push_back(lowerFactor(p, f, none));
  // Several `if` guards are conjoined, in source order.
  for (const auto& c : p.guards) {
    ir::Expr e = lower(c.get(), none);
    if (!g.guard) {
      g.guard = std::move(e);
    } else {
      ir::Expr both;
      both.op = ir::Op::And;
      both.type = e.type;
      both.children.push_back(std::move(*g.guard));
      both.children.push_back(std::move(e));
      g.guard = std::move(both);
    }
  }
  if (!p.accepts.empty()) g.accept = p.accepts[0]->number;
  if (!p.fallbacks.empty()) g.fallback = p.fallbacks[0]->number;
  g.exploreAccepted = !p.explores.empty() && p.explores[0].name == "accepted";
  for (const auto& rule : p.learnRules) g.learnRules.push_back(lowerLearnRule(p, rule, none));
  checkGeneratorInstances(p, g);
  warnIfUnmatched(p, g);
  warnIfNeverTogether(p, g);
  g_.generators.push_back(std::move(g));
}

ir::ModelFactor Lowerer::lowerFactor(const PersonalDecl& p, const ModelFactor& f, Ctx& none) {
  ir::ModelFactor mf;
  mf.label = generatorFactorName(p, f);
  // The generator checker accepts only the kinds, directions, scales and ratings OpNames spells.
  mf.kind = ir::factorKindFromName(f.kind.name).value_or(ir::FactorKind::Interval);
  mf.span = span(f.range);
  std::vector<const Arg*> positional;
  for (const auto& a : f.args) {
    if (a.name.name.empty())
      positional.push_back(&a);
    else if (a.name.name == "prompt")
      mf.prompt = a.value->text;
    else if (a.name.name == "learning")
      mf.learning = a.value->text;
    else if (a.name.name == "scale")
      mf.scale = ir::textScaleFromName(a.value->text).value_or(ir::TextScale::Absolute);
    else if (a.name.name == "rating")
      mf.rating = ir::textRatingFromName(a.value->text).value_or(ir::TextRating::Digits);
    else if (a.name.name == "context")
      lowerTextContext(p, *a.value, mf, none);
  }
  // Positional arguments: the feature, then its range, then a threshold's direction.
  if (!positional.empty()) {
    mf.feature = lower(positional[0]->value.get(), none);
    for (int i : paramsRead(positional[0]->value.get())) mf.params.push_back(p.params[i].name.name);
  }
  if (positional.size() >= 2 && positional[1]->value->kind == ExprKind::Range) {
    mf.lo = constNumber(positional[1]->value->operands[0].get());
    mf.hi = constNumber(positional[1]->value->operands[1].get());
  }
  if (positional.size() >= 3)
    mf.direction = ir::thresholdDirectionFromName(positional[2]->value->text).value_or(ir::ThresholdDirection::None);
  return mf;
}

void Lowerer::lowerTextContext(const PersonalDecl& p, const Expr& context, ir::ModelFactor& mf, Ctx& none) {
  std::vector<const Expr*> entries;
  if (context.kind == ExprKind::List) {
    for (const auto& e : context.operands) entries.push_back(e.get());
  } else {
    entries.push_back(&context);
  }
  for (const Expr* e : entries) {
    ir::ContextEntry entry{e->text, lower(e, none), {}};
    for (int i : paramsRead(e)) entry.params.push_back(p.params[i].name.name);
    mf.context.push_back(std::move(entry));
  }
}

ir::LearnRule Lowerer::lowerLearnRule(const PersonalDecl& p, const LearnRule& rule, Ctx& none) {
  ir::LearnRule r;
  r.event = rule.event.name;
  r.span = span(rule.range);
  for (const auto& b : rule.binders) {
    const std::string& n = b->name.name;
    r.binders.push_back(n.empty() ? "_" : n);
    // A binder named like a parameter or a pattern's capture binds it; any other name is a local.
    bool binds = false;
    for (const auto& prm : p.params) binds = binds || prm.name.name == n;
    for (const auto& c : p.captures) binds = binds || c.name == n;
    r.binds.push_back(binds && !n.empty() ? n : "");
  }
  for (const auto& l : rule.labels) r.labels.push_back({l.factor.name, lower(l.value.get(), none)});
  if (rule.condition) r.condition = lower(rule.condition.get(), none);
  return r;
}

void Lowerer::warnIfUnmatched(const PersonalDecl& p, const ir::Generator& g) {
  for (std::size_t i = 0; i < p.params.size(); ++i) {
    const ir::TypeDesc want = g.params[i].type;
    const PatternClause* pat = nullptr;
    for (const auto& pc : p.patterns) {
      if (pc.paramIndex == static_cast<int>(i)) pat = &pc;
    }
    std::optional<GlobPattern> glob;
    std::optional<std::regex> re;
    std::string error;
    std::size_t at = 0;
    if (pat && pat->kind == PatternKind::Glob) glob = parseGlob(pat->pattern, error, at);
    if (pat && pat->kind == PatternKind::Regex) re = compileRegex(pat->pattern, error);
    bool any = false;
    for (const auto& v : g_.variables) {
      if (v.type.spelling != want.spelling) continue;
      std::map<std::string, std::string> b;
      if (pat == nullptr || (glob && matchGlob(*glob, v.name, b)) || (re && std::regex_match(v.name, *re))) {
        any = true;
        break;
      }
    }
    if (!any) {
      Diagnostic& d = diags_.warning("W0401", pat ? pat->patternRange : p.params[i].name.range,
                                     fmt::format("no {} variable of any task matches parameter '{}' of generator '{}'",
                                                 want.spelling, p.params[i].name.name, p.name.name));
      d.help("`cbtlc emit FILE` lists every variable's name and type");
    }
  }
}

// W0403: every parameter matches some variable (else W0401 says so), but no task has a tuple of them that agrees on
// the patterns' captures, so the generator makes no constraint at all. Searched per task with a step budget; a
// search that runs out of steps warns about nothing.
void Lowerer::warnIfNeverTogether(const PersonalDecl& p, const ir::Generator& g) {
  const std::size_t arity = p.params.size();
  std::vector<std::optional<GlobPattern>> globs(arity);
  std::vector<std::optional<std::regex>> regexes(arity);
  for (const auto& pc : p.patterns) {
    if (pc.paramIndex < 0 || static_cast<std::size_t>(pc.paramIndex) >= arity) return;
    std::string error;
    std::size_t at = 0;
    if (pc.kind == PatternKind::Glob)
      globs[pc.paramIndex] = parseGlob(pc.pattern, error, at);
    else
      regexes[pc.paramIndex] = compileRegex(pc.pattern, error);
  }
  for (std::size_t i = 0; i < arity; ++i)
    if (!globs[i] && !regexes[i]) return;  // no pattern or a malformed one: reported elsewhere
  // Per task, per parameter: the variables that match it alone.
  std::vector<bool> matchedSomewhere(arity, false);
  std::size_t budget = 1000000;
  for (const auto& task : g_.tasks) {
    std::vector<std::vector<const ir::Variable*>> candidates(arity);
    for (ir::VarId id : task.vars) {
      const ir::Variable& v = g_.variables[id];
      for (std::size_t i = 0; i < arity; ++i) {
        if (v.type.spelling != g.params[i].type.spelling) continue;
        std::map<std::string, std::string> b;
        if ((globs[i] && matchGlob(*globs[i], v.name, b)) || (regexes[i] && std::regex_match(v.name, *regexes[i])))
          candidates[i].push_back(&v);
      }
    }
    bool complete = true;
    for (std::size_t i = 0; i < arity; ++i) {
      matchedSomewhere[i] = matchedSomewhere[i] || !candidates[i].empty();
      complete = complete && !candidates[i].empty();
    }
    if (!complete) continue;
    // Depth-first over the parameters, keeping the captures bound so far.
    std::function<bool(std::size_t, std::map<std::string, std::string>&)> extend =
        [&](std::size_t i, std::map<std::string, std::string>& bindings) -> bool {
      if (i == arity) return true;
      for (const ir::Variable* v : candidates[i]) {
        if (budget == 0) return true;  // undecided: assume it matches
        --budget;
        std::map<std::string, std::string> next = bindings;
        if (globs[i] && !matchGlob(*globs[i], v->name, next)) continue;
        if (extend(i + 1, next)) return true;
      }
      return false;
    };
    std::map<std::string, std::string> none;
    if (extend(0, none)) return;
  }
  for (std::size_t i = 0; i < arity; ++i)
    if (!matchedSomewhere[i]) return;  // W0401 covers a parameter that matches nothing
  std::string captures;
  for (const auto& c : p.captures) captures += (captures.empty() ? "{" : ", {") + c.name + "}";
  Diagnostic& d = diags_.warning(
      "W0403", p.name.range,
      captures.empty()
          ? fmt::format("generator '{}' creates no constraint: no task has a variable for every parameter", p.name.name)
          : fmt::format("generator '{}' creates no constraint: its patterns match variables, but never ones that "
                        "agree on {} in one task",
                        p.name.name, captures));
  for (const auto& pc : p.patterns) d.note(fmt::format("'{}' matches on its own", pc.param.name), pc.patternRange);
  d.help("`cbtlc emit FILE` lists every task's variables; a capture must bind the same text in every pattern");
}

}  // namespace cbtl::detail
