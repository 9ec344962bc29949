// lower: what the runtime will build or evaluate from the graph, measured before it does, for the limits of
// CompileLimits that lowering checks besides the graph's size: quantifier nests (E0320) and personalized
// generator instances (E0418). Both grow with a product (of set sizes, of matching variables), so a few lines
// of source can ask for more work than any machine can do; each is counted without doing that work.
#include "compiler/lower/LoweringInternal.h"

#include "ir/Pattern.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <regex>

namespace cbtl::detail {
namespace {

constexpr std::size_t kSaturated = std::numeric_limits<std::size_t>::max();

std::size_t saturatingMul(std::size_t a, std::size_t b) {
  if (a != 0 && b > kSaturated / a) return kSaturated;
  return a * b;
}

std::string countText(std::size_t n) {
  return n == kSaturated ? fmt::format("more than {}", kSaturated) : std::to_string(n);
}

const FuncDecl* userCallee(const Expr& e) {
  if (e.kind != ExprKind::Call || e.ref.kind != RefKind::Function) return nullptr;
  const auto* f = static_cast<const FuncDecl*>(e.ref.decl);
  return f->isExtern || !f->body ? nullptr : f;
}

}  // namespace

// --- quantifier nests ---------------------------------------------------------------------------------------

void Lowerer::checkQuantifierNest(const Expr& quantifier, const Ctx& ctx) {
  if (quantifierNesting_ > 0) return;  // inside a nest already measured as a whole
  quantifierBindings(&quantifier, ctx, true);
}

std::size_t Lowerer::setSize(const Expr* set, const Ctx& ctx) {
  if (set == nullptr) return 1;
  if (set->kind == ExprKind::Name && set->ref.kind == RefKind::EnumType)
    return static_cast<const EnumDecl&>(*set->ref.decl).members.size();
  if (set->kind == ExprKind::Name && set->ref.kind == RefKind::ItemSet)
    return static_cast<const ItemsDecl&>(*set->ref.decl).entries.size();
  if (set->kind == ExprKind::Name && set->ref.kind == RefKind::Const) {  // a constant list (constants are acyclic)
    const auto* c = static_cast<const ConstDecl*>(set->ref.decl);
    return c->index ? 1 : setSize(c->value.get(), ctx);
  }
  if (set->kind == ExprKind::List) return set->operands.size();
  if (set->kind == ExprKind::Range) {
    auto lo = evalConst(set->operands[0].get(), ctx), hi = evalConst(set->operands[1].get(), ctx);
    if (!lo || !hi || lo->kind != CVal::Kind::Int || hi->kind != CVal::Kind::Int) return 1;
    if (hi->number < lo->number) return 0;
    const auto span = static_cast<unsigned long long>(hi->number) - static_cast<unsigned long long>(lo->number);
    return span >= kSaturated - 1 ? kSaturated : static_cast<std::size_t>(span) + 1;
  }
  return 1;  // not known at compile time (an observation, a variable's bounds): not counted
}

std::size_t Lowerer::quantifierBindings(const Expr* e, const Ctx& ctx, bool report) {
  if (e == nullptr) return 1;
  std::size_t inner = 1;
  for (const auto& op : e->operands) inner = std::max(inner, quantifierBindings(op.get(), ctx, report));
  for (const auto& a : e->args) inner = std::max(inner, quantifierBindings(a.value.get(), ctx, report));
  if (const FuncDecl* f = userCallee(*e)) inner = std::max(inner, functionBindings(*f));
  if (e->kind != ExprKind::Quantifier || !e->binder) return inner;
  // The where clause and the body are evaluated once per combination of the binders' values.
  std::size_t total = inner;
  const std::size_t members = setSize(e->binder->set.get(), ctx);
  for (std::size_t i = 0; i < e->binder->names.size(); ++i) total = saturatingMul(total, members);
  const std::size_t ofSet = quantifierBindings(e->binder->set.get(), ctx, report);
  // Reported at the innermost quantifier that takes the nest over the limit, once.
  if (report && total > CompileLimits::kMaxQuantifierBindings && inner <= CompileLimits::kMaxQuantifierBindings &&
      quantifiersReported_.insert(e).second) {
    diags_
        .error("E0320", e->range,
               fmt::format("this quantifier ranges over {} combinations of values ({} binder{} over {} members{}), "
                           "more than the limit of {}",
                           countText(total), e->binder->names.size(), e->binder->names.size() == 1 ? "" : "s", members,
                           inner > 1 ? fmt::format(", times {} for the quantifiers inside it", inner) : "",
                           CompileLimits::kMaxQuantifierBindings))
        .help(
            "the runtime evaluates the body once per combination each time it checks a candidate: range over a "
            "smaller set, or over the members that matter (an enum or item set of them, a 'where' cannot help)");
  }
  return std::max(total, ofSet);
}

std::size_t Lowerer::functionBindings(const FuncDecl& f) {
  if (const auto it = functionBindings_.find(&f); it != functionBindings_.end()) return it->second;
  functionBindings_[&f] = 1;  // check-types refused recursion; this only guards the walk
  // A function's body is measured (and reported) where it is lowered; here it only multiplies its callers.
  Ctx none;
  const std::size_t n = quantifierBindings(f.body.get(), none, false);
  functionBindings_[&f] = n;
  return n;
}

// --- generator instances ------------------------------------------------------------------------------------

namespace {

struct ParamMatcher {
  std::vector<GlobPattern> globs;
  std::vector<std::regex> regexes;
};

// The runtime's instantiation (runtime/core/Personalization.cpp, personalize) replayed without building
// anything: every tuple of distinct candidates whose names the parameters' patterns match with agreeing
// captures. Counts instances and steps (a candidate tried, a pattern tested) and stops past the budgets.
struct InstanceCounter {
  InstanceCounter(const ir::ConstraintGraph& g, const std::vector<ParamMatcher>& m) : graph(g), matchers(m) {}

  const ir::ConstraintGraph& graph;
  const std::vector<ParamMatcher>& matchers;
  std::vector<const std::vector<ir::VarId>*> candidates;  // per parameter
  std::size_t instances = 0, steps = 0;
  std::size_t maxInstances = 0, maxSteps = 0;
  std::vector<ir::VarId> chosen;
  std::map<std::string, std::string> bindings;

  bool over() const { return instances > maxInstances || steps > maxSteps; }

  void extend(std::size_t i) {
    if (i == chosen.size()) {
      ++instances;
      return;
    }
    for (ir::VarId v : *candidates[i]) {
      if (over()) return;
      ++steps;
      if (std::find(chosen.begin(), chosen.begin() + static_cast<long>(i), v) != chosen.begin() + static_cast<long>(i))
        continue;
      const std::string& name = graph.variables.at(v).name;
      auto saved = bindings;
      bool ok = true;
      for (const auto& glob : matchers[i].globs) ok = ok && (++steps, matchGlob(glob, name, bindings));
      for (const auto& re : matchers[i].regexes) ok = ok && (++steps, std::regex_match(name, re));
      if (ok) {
        chosen[i] = v;
        extend(i + 1);
      }
      bindings = std::move(saved);
    }
  }
};

}  // namespace

void Lowerer::checkGeneratorInstances(const PersonalDecl& p, const ir::Generator& g) {
  if (generatorsTooLarge_ || g.params.empty()) return;
  std::vector<ParamMatcher> matchers(g.params.size());
  for (const auto& pat : g.patterns) {
    if (pat.paramIndex >= matchers.size()) continue;
    std::string error;
    std::size_t at = 0;
    if (pat.kind == ir::PatternKind::Regex) {
      if (auto re = compileRegex(pat.text, error)) matchers[pat.paramIndex].regexes.push_back(*re);
    } else if (auto glob = parseGlob(pat.text, error, at)) {
      matchers[pat.paramIndex].globs.push_back(*glob);
    }
  }
  for (std::size_t t = 0; t < g_.tasks.size(); ++t) {
    InstanceCounter counter(g_, matchers);
    counter.maxInstances = CompileLimits::kMaxGeneratorInstances - generatorInstances_;
    counter.maxSteps = CompileLimits::kMaxGeneratorMatchSteps - generatorMatchSteps_;
    counter.chosen.assign(g.params.size(), 0);
    // The runtime looks at every variable of the task for each parameter's type.
    counter.steps = g.params.size() * g_.tasks[t].vars.size();
    for (const auto& prm : g.params) counter.candidates.push_back(&candidatesOfType(t, prm.type.spelling));
    counter.extend(0);
    if (!counter.over()) {
      generatorInstances_ += counter.instances;
      generatorMatchSteps_ += counter.steps;
      continue;
    }
    generatorsTooLarge_ = true;
    reportTooManyInstances(p, g_.tasks[t].name, counter.instances > counter.maxInstances, counter.candidates);
    return;
  }
}

void Lowerer::reportTooManyInstances(const PersonalDecl& p, const std::string& task, bool instances,
                                     const std::vector<const std::vector<ir::VarId>*>& candidates) {
  std::string sizes;
  for (const auto* c : candidates) sizes += (sizes.empty() ? "" : " x ") + std::to_string(c->size());
  const std::size_t before = instances ? generatorInstances_ : generatorMatchSteps_;
  const std::string what =
      instances ? fmt::format("generator '{}' takes the program past {} generator instances", p.name.name,
                              CompileLimits::kMaxGeneratorInstances)
                : fmt::format("finding the instances of generator '{}' takes the program past {} matching steps",
                              p.name.name, CompileLimits::kMaxGeneratorMatchSteps);
  diags_
      .error("E0418", p.whenRanges.empty() ? p.name.range : p.whenRanges.front(),
             fmt::format("{} in task '{}' (its parameters have {} candidate variables; the generators before it "
                         "took {})",
                         what, task, sizes, before))
      .help(
          "the runtime makes one instance for every tuple of distinct variables the patterns match: make the "
          "patterns match fewer variables (a capture the parameters share, e.g. \"*used[{ing}]\" and "
          "\"*quantity[{ing}]\", pairs only the variables of one ingredient)");
}

const std::vector<ir::VarId>& Lowerer::candidatesOfType(std::size_t task, const std::string& type) {
  auto it = candidatesByTask_.find(task);
  if (it == candidatesByTask_.end()) {
    it = candidatesByTask_.emplace(task, std::map<std::string, std::vector<ir::VarId>>{}).first;
    for (ir::VarId v : g_.tasks[task].vars) it->second[g_.variables.at(v).type.spelling].push_back(v);
  }
  return it->second[type];
}

}  // namespace cbtl::detail
