#include "compiler/sema/GeneratorChecker.h"

#include "compiler/sema/Type.h"
#include "compiler/util/Suggest.h"
#include "ir/Pattern.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

namespace cbtl {

const std::vector<std::string>& modelKinds() {
  static const std::vector<std::string> kinds = {"interval", "threshold", "table", "text"};
  return kinds;
}

namespace {

void collectParams(const Expr* e, std::set<int>& out) {
  if (e == nullptr) return;
  if (e->kind == ExprKind::Name && e->ref.kind == RefKind::Param && e->ref.decl != nullptr &&
      e->ref.decl->kind == DeclKind::Personal) {
    out.insert(e->ref.index);
  }
  for (const auto& op : e->operands) collectParams(op.get(), out);
  for (const auto& a : e->args) collectParams(a.value.get(), out);
  if (e->binder) collectParams(e->binder->set.get(), out);
}

class GenChecker {
 public:
  explicit GenChecker(DiagnosticEngine& diags) : diags_(diags) {}

  void check(PersonalDecl& g) {
    if (g.params.empty()) {
      diags_.error("E0413", g.name.range, fmt::format("generator '{}' has no parameters", g.name.name))
          .help("its arity is the number of parameters: personal name(x: real) { ... }");
    }
    for (const auto& p : g.params) {
      if (p.type.resolved && !p.type.resolved->isError() && !p.type.resolved->isVariableType()) {
        diags_.error("E0415", p.type.range,
                     fmt::format("a generator parameter cannot have type {}", p.type.resolved->spelling));
      }
    }
    checkPatterns(g);
    checkModel(g);
    checkProbability(g.accepts, "accept", /*allowZero=*/false);
    checkProbability(g.fallbacks, "fallback", /*allowZero=*/true);
    checkExplore(g);
    for (auto& rule : g.learnRules) checkRule(g, rule);
    if (g.learnRules.empty()) {
      diags_.warning("W0402", g.name.range,
                     fmt::format("generator '{}' has no learning rule, so it never learns", g.name.name));
    }
  }

 private:
  int paramIndex(const PersonalDecl& g, const std::string& name) const {
    for (std::size_t i = 0; i < g.params.size(); ++i) {
      if (g.params[i].name.name == name) return static_cast<int>(i);
    }
    return -1;
  }

  void checkPatterns(PersonalDecl& g) {
    for (std::size_t i = 1; i < g.whenRanges.size(); ++i) {
      diags_.error("E0414", g.whenRanges[i],
                   "a generator has one 'when' clause; list all patterns in it, separated by ','");
    }
    std::set<int> seen;
    bool namedUnknown = false;  // a pattern for a misspelt parameter: its help names the one meant
    for (auto& p : g.patterns) {
      p.paramIndex = paramIndex(g, p.param.name);
      // Patterns of a second 'when' clause (E0414 above) are not also reported as second patterns.
      if (g.whenRanges.size() > 1 && p.param.range.begin >= g.whenRanges[1].begin) continue;
      if (p.paramIndex < 0) {
        std::vector<std::string> names;
        for (const auto& prm : g.params) names.push_back(prm.name.name);
        Diagnostic& d =
            diags_.error("E0402", p.param.range,
                         fmt::format("'{}' is not a parameter of generator '{}'", p.param.name, g.name.name));
        const std::string guess = closestMatch(p.param.name, names);
        if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
        namedUnknown = true;
        continue;
      }
      if (!seen.insert(p.paramIndex).second) {
        diags_.error("E0402", p.param.range, fmt::format("parameter '{}' has two patterns", p.param.name));
        continue;
      }
      std::string error;
      if (p.kind == PatternKind::Glob) {
        std::size_t at = 0;
        auto glob = parseGlob(p.pattern, error, at);
        if (!glob) {
          // +1 skips the opening quote of the string literal.
          const auto begin = static_cast<std::uint32_t>(p.patternRange.begin + 1 + at);
          diags_.error("E0401", SourceRange{p.patternRange.file, begin, begin + 1},
                       fmt::format("malformed glob: {}", error));
          continue;
        }
        for (const auto& c : glob->captures) {
          if (std::none_of(g.captures.begin(), g.captures.end(), [&](const Ident& x) { return x.name == c; })) {
            g.captures.push_back(Ident{c, p.patternRange});
          }
        }
      } else if (!compileRegex(p.pattern, error)) {
        diags_.error("E0401", p.patternRange, fmt::format("malformed regular expression: {}", error));
      }
    }
    // Without a pattern a parameter would match every variable of its type: almost never what is meant, and
    // silent (the constraint then judges variables nobody asked it to).
    if (g.whenRanges.empty() || namedUnknown) return;
    for (std::size_t i = 0; i < g.params.size(); ++i) {
      if (seen.count(static_cast<int>(i)) > 0 || g.params[i].name.name.empty()) continue;
      const std::string type = g.params[i].type.resolved ? g.params[i].type.resolved->spelling : "its type's";
      diags_
          .error("E0417", g.params[i].name.range,
                 fmt::format("parameter '{}' of generator '{}' has no pattern in its 'when' clause, so it would match "
                             "every {} variable",
                             g.params[i].name.name, g.name.name, type))
          .help(fmt::format("add `{} ~ \"NAME\"` to the 'when' clause (\"*\" matches every name, if that is meant)",
                            g.params[i].name.name));
    }
  }

  void needArgs(const ModelFactor& f, std::size_t positional, const std::string& form) {
    std::size_t count = 0;
    for (const auto& a : f.args) count += a.name.name.empty() ? 1 : 0;
    if (count != positional) {
      diags_.error("E0406", f.range,
                   fmt::format("{} takes {} positional argument{}: {}", f.kind.name, positional,
                               positional == 1 ? "" : "s", form));
    }
  }

  // Returns (lo, hi) if the expression is a literal range of constant numbers.
  bool constantRange(const Expr* e) {
    if (e == nullptr || e->kind != ExprKind::Range) return false;
    auto isNum = [](const Expr* x) {
      if (x->kind == ExprKind::Number) return true;
      return x->kind == ExprKind::Unary && x->unaryOp == UnaryOp::Neg && x->operands[0]->kind == ExprKind::Number;
    };
    return isNum(e->operands[0].get()) && isNum(e->operands[1].get());
  }

  static double literal(const Expr* x) { return x->kind == ExprKind::Number ? x->number : -x->operands[0]->number; }

  // A model's prior `lo .. hi` (a constant range, checked above) must not be inverted: `interval(t, 85 .. 40)`
  // would learn in an empty set, and every candidate would be rejected once something is liked.
  void priorInOrder(const Arg& prior, const char* kind) {
    const Expr* e = prior.value.get();
    const double lo = literal(e->operands[0].get()), hi = literal(e->operands[1].get());
    if (lo > hi) {
      diags_
          .error("E0311", prior.range,
                 fmt::format("the prior of {} {} model is empty: {} > {}", std::string(kind) == "interval" ? "an" : "a",
                             kind, fmt::format("{}", lo), fmt::format("{}", hi)))
          .help(fmt::format("write the smaller bound first: {} .. {}", hi, lo));
    } else if (lo == hi) {
      diags_.error(
          "E0311", prior.range,
          fmt::format("the prior of a {} model is a single point ({} .. {}): there is nothing to learn", kind, lo, hi));
    }
  }

  void realFeature(const ModelFactor& f, const Expr* feature) {
    if (feature == nullptr || feature->type == nullptr || feature->type->isError()) return;
    if (!feature->type->isNumeric()) {
      diags_
          .error("E0405", feature->range,
                 fmt::format("the feature of {} {} model must be real-valued, but this is {}",
                             f.kind.name == "interval" ? "an" : "a", f.kind.name, feature->type->spelling))
          .help("compute a number from the parameters, e.g. distance(p, center) or occlusion(c)");
    }
  }

  void checkModel(PersonalDecl& g) {
    if (g.modelRanges.empty()) {
      diags_.error("E0403", g.name.range, fmt::format("generator '{}' has no 'model' clause", g.name.name))
          .help("add one, e.g. model interval(x, 0 .. 1);");
      return;
    }
    for (std::size_t i = 1; i < g.modelRanges.size(); ++i) {
      diags_.error("E0403", g.modelRanges[i], "a generator has one 'model' clause; combine factors with '*'");
    }
    std::set<std::string> labels;
    for (auto& f : g.factors) {
      const std::string& k = f.kind.name;
      if (!f.label.name.empty() && !labels.insert(f.label.name).second) {
        diags_.error("E0406", f.label.range, fmt::format("two factors are named '{}'", f.label.name));
      }
      const Expr* first = nullptr;
      for (const auto& a : f.args) {
        if (a.name.name.empty()) {
          first = a.value.get();
          break;
        }
      }
      if (k == "interval") {
        needArgs(f, 2, "interval(feature, lo .. hi)");
        realFeature(f, first);
        if (f.args.size() >= 2 && !constantRange(f.args[1].value.get())) {
          diags_.error("E0406", f.args[1].range,
                       "the prior bounds of an interval model are a range of literal numbers, lo .. hi");
        } else if (f.args.size() >= 2) {
          priorInOrder(f.args[1], "interval");
        }
      } else if (k == "threshold") {
        needArgs(f, 3, "threshold(feature, lo .. hi, above|below)");
        realFeature(f, first);
        if (f.args.size() >= 2 && !constantRange(f.args[1].value.get())) {
          diags_.error("E0406", f.args[1].range,
                       "the prior bounds of a threshold model are a range of literal numbers, lo .. hi");
        } else if (f.args.size() >= 2) {
          priorInOrder(f.args[1], "threshold");
        }
        if (f.args.size() >= 3) {
          const Expr* dir = f.args[2].value.get();
          if (dir->kind != ExprKind::Name || (dir->text != "above" && dir->text != "below")) {
            diags_.error("E0406", f.args[2].range, "the direction of a threshold model is 'above' or 'below'");
          }
        }
      } else if (k == "table") {
        needArgs(f, 1, "table(key)");
        if (first && first->type && !first->type->isError() && !first->type->isDiscrete()) {
          diags_.error("E0406", first->range,
                       fmt::format("a table model needs a discrete key (enum, item, int, bool or text), not {}",
                                   first->type->spelling));
        }
      } else if (k == "text") {
        needArgs(f, 1,
                 "text(subject, prompt: \"...\", learning: \"...\", scale: relative|absolute, rating: digits|options, "
                 "context: [name, ...])");
        if (first && first->type && !first->type->isError() && first->type->kind != TypeKind::Item &&
            first->type->kind != TypeKind::Enum && first->type->kind != TypeKind::Text) {
          diags_.error(
              "E0406", first->range,
              fmt::format("a text model's subject is an item, an enum or text, not {}", first->type->spelling));
        }
        for (const auto& a : f.args) {
          if (a.name.name.empty()) continue;
          if (a.name.name == "prompt" || a.name.name == "learning") {
            if (a.value->kind != ExprKind::String)
              diags_.error("E0406", a.range, fmt::format("'{}' must be a string", a.name.name));
          } else if (a.name.name == "scale") {
            if (a.value->kind != ExprKind::Name || (a.value->text != "relative" && a.value->text != "absolute")) {
              diags_.error("E0406", a.range, "'scale' is 'relative' or 'absolute'");
            }
          } else if (a.name.name == "rating") {
            if (a.value->kind != ExprKind::Name || (a.value->text != "digits" && a.value->text != "options")) {
              diags_.error("E0406", a.range, "'rating' is 'digits' or 'options'");
            }
          } else if (a.name.name == "context") {
            checkTextContext(a);
          } else {
            diags_.error("E0406", a.name.range, fmt::format("a text model has no argument '{}'", a.name.name))
                .help("its named arguments are prompt, learning, scale, rating and context");
          }
        }
      } else {
        Diagnostic& d = diags_.error("E0404", f.kind.range, fmt::format("unknown model kind '{}'", k));
        const std::string guess = closestMatch(k, modelKinds());
        if (!guess.empty())
          d.help(fmt::format("did you mean '{}'?", guess));
        else
          d.help("known kinds: interval, threshold, table, text");
        continue;
      }
      if (k != "text") {
        for (const auto& a : f.args) {
          if (!a.name.name.empty()) diags_.error("E0406", a.name.range, fmt::format("{} takes no named arguments", k));
        }
      }
    }
    for (const auto& key : g.perKeys) checkKey(g, key);
  }

  // A key is a capture, a discrete parameter, or a discrete expression over parameters, observations and
  // constants. Decision variables are refused: a key names which model an instance uses, and an instance must
  // keep its model while the solver changes the candidate.
  void checkKey(const PersonalDecl& g, const PerKey& key) {
    const PerKeyKind kind = perKeyKind(g, key);
    if (kind == PerKeyKind::Capture) return;
    if (kind == PerKeyKind::Invalid) {
      diags_
          .error("E0412", key.spelling.range,
                 fmt::format("'{}' is neither a capture of the 'when' patterns, a parameter, nor a name in scope",
                             key.spelling.name))
          .help(
              "a key is a capture, a discrete parameter, or an expression over the parameters such as "
              "kindOf[p] or p.kind");
      return;
    }
    const Type* type = key.expr->type;
    if (type != nullptr && !type->isError() && !type->isDiscrete()) {
      diags_
          .error("E0412", key.spelling.range,
                 fmt::format("a 'per' key must be discrete (enum, item, int, bool or text), but '{}' is {}",
                             key.spelling.name, type->spelling))
          .help("one model is learned per distinct value of the key; a real number would give one per reading");
    }
    if (const Expr* v = findVariableRead(key.expr.get())) {
      diags_.error("E0412", v->range, fmt::format("a 'per' key cannot read the decision variable '{}'", v->text))
          .help("a key may read the generator's parameters, observations and constants; make it a parameter");
    }
  }

  static const Expr* findVariableRead(const Expr* e) {
    if (e == nullptr) return nullptr;
    if (e->kind == ExprKind::Name && e->ref.kind == RefKind::Variable) return e;
    for (const auto& op : e->operands) {
      if (const Expr* v = findVariableRead(op.get())) return v;
    }
    for (const auto& a : e->args) {
      if (const Expr* v = findVariableRead(a.value.get())) return v;
    }
    if (e->binder) return findVariableRead(e->binder->set.get());
    return nullptr;
  }

  // `context: name` or `context: [name, ...]`: observations or generator parameters of a discrete scalar type, each
  // named once. The names are the keys the text models see, so an expression (which has no name) is not allowed.
  void checkTextContext(const Arg& a) {
    std::vector<const Expr*> entries;
    if (a.value->kind == ExprKind::List) {
      for (const auto& e : a.value->operands) entries.push_back(e.get());
      if (entries.empty()) diags_.error("E0406", a.value->range, "an empty context; leave 'context' out instead");
    } else {
      entries.push_back(a.value.get());
    }
    std::set<std::string> seen;
    for (const Expr* e : entries) {
      const bool named =
          e->kind == ExprKind::Name && (e->ref.kind == RefKind::Observation || e->ref.kind == RefKind::Param);
      if (!named) {
        if (e->kind != ExprKind::Name || e->ref.kind != RefKind::Unresolved)  // unknown names are reported already
          diags_.error("E0406", e->range, "a text model's context names observations or generator parameters")
              .help("write the names, e.g. context: [foodOnPlate, mealSetting]");
        continue;
      }
      if (!seen.insert(e->text).second) {
        diags_.error("E0406", e->range, fmt::format("'{}' is in the context twice", e->text));
        continue;
      }
      if (e->type && !e->type->isError() && !e->type->isDiscrete()) {
        diags_
            .error("E0406", e->range,
                   fmt::format("a context value is text, an enum, an item, bool or int, not {}", e->type->spelling))
            .help("the models compare contexts by equality; a continuous value is never seen twice");
      }
    }
  }

  void checkProbability(const std::vector<ExprPtr>& clauses, const char* what, bool allowZero) {
    for (std::size_t i = 0; i < clauses.size(); ++i) {
      const Expr* e = clauses[i].get();
      if (i > 0) {
        diags_.error("E0414", e->range, fmt::format("a generator has one '{}' clause", what));
        continue;
      }
      const bool literal = e->kind == ExprKind::Number && e->text != "<missing>";
      if (!literal || e->number > 1 || e->number < 0 || (!allowZero && e->number == 0)) {
        diags_.error("E0411", e->range,
                     fmt::format("'{}' takes a number in {}", what, allowZero ? "[0, 1]" : "(0, 1]"));
      }
    }
  }

  void checkExplore(const PersonalDecl& g) {
    for (std::size_t i = 0; i < g.explores.size(); ++i) {
      const Ident& mode = g.explores[i];
      if (i > 0) {
        diags_.error("E0414", mode.range, "a generator has one 'explore' clause");
        continue;
      }
      if (mode.name != "accepted" && mode.name != "anywhere") {
        Diagnostic& d = diags_.error("E0416", mode.range, fmt::format("unknown exploration mode '{}'", mode.name));
        const std::string guess = closestMatch(mode.name, {"accepted", "anywhere"});
        d.help(guess.empty() ? "write 'explore accepted;' or 'explore anywhere;'"
                             : fmt::format("did you mean '{}'?", guess));
      }
    }
  }

  void checkRule(const PersonalDecl& g, LearnRule& rule) {
    if (rule.eventRef.kind != RefKind::Feedback) return;  // reported by name resolution
    const auto& ev = static_cast<const FeedbackDecl&>(*rule.eventRef.decl);
    if (rule.binders.size() != ev.params.size()) {
      diags_
          .error("E0407", rule.event.range,
                 fmt::format("event '{}' has {} parameter{}, but the rule binds {}", ev.name.name, ev.params.size(),
                             ev.params.size() == 1 ? "" : "s", rule.binders.size()))
          .note("declared here", ev.name.range);
      return;
    }
    std::set<std::string> bound;
    for (std::size_t i = 0; i < rule.binders.size(); ++i) {
      const std::string& b = rule.binders[i]->name.name;
      if (b.empty()) continue;
      const int pi = paramIndex(g, b);
      if (pi >= 0) {
        const Type* want = g.params[pi].type.resolved;
        const Type* got = ev.params[i].type.resolved;
        if (want && got && !want->isError() && !got->isError() && !assignable(want, got)) {
          diags_.error("E0408", rule.binderRanges[i],
                       fmt::format("binder '{}' binds parameter '{}' of type {}, but the event gives {}", b, b,
                                   want->spelling, got->spelling));
        }
        bound.insert(b);
      } else if (std::any_of(g.captures.begin(), g.captures.end(), [&](const Ident& c) { return c.name == b; })) {
        bound.insert(b);
      }
    }
    // Factors of a second 'model' clause (already an error) do not make the model a product.
    const bool product = g.modelRanges.size() == 1 && g.factors.size() > 1;
    std::set<std::string> labelled;
    for (auto& label : rule.labels) {
      if (label.value && label.value->type && !label.value->type->isError() &&
          label.value->type->kind != TypeKind::Bool) {
        diags_.error("E0409", label.value->range,
                     fmt::format("a label must be bool, but this is {}", label.value->type->spelling));
      }
      if (label.factor.name.empty()) {
        if (product) {
          diags_.error("E0409", label.value->range,
                       "the model is a product; say which factor this labels, as in 'temp: good'");
        }
        for (const auto& f : g.factors) labelled.insert(factorName(g, f));
        continue;
      }
      bool found = false;
      for (const auto& f : g.factors) {
        if (factorName(g, f) == label.factor.name) found = true;
      }
      if (!found) {
        std::vector<std::string> names;
        for (const auto& f : g.factors) names.push_back(factorName(g, f));
        Diagnostic& d = diags_.error("E0409", label.factor.range,
                                     fmt::format("the model has no factor named '{}'", label.factor.name));
        const std::string guess = closestMatch(label.factor.name, names);
        if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
        continue;
      }
      labelled.insert(label.factor.name);
    }
    // Every parameter and key that a labelled factor reads must be bound by this rule.
    for (const auto& f : g.factors) {
      if (!labelled.count(factorName(g, f))) continue;
      std::set<int> reads;
      for (const auto& a : f.args) collectParams(a.value.get(), reads);
      for (int pi : reads) {
        const std::string& name = g.params[pi].name.name;
        if (!bound.count(name)) {
          diags_
              .error("E0410", rule.range,
                     fmt::format("this rule labels factor '{}', which reads parameter '{}', but does not bind it",
                                 factorName(g, f), name))
              .help(fmt::format("name the event binder '{}' in the position that carries it", name));
        }
      }
    }
    for (const auto& key : g.perKeys) {
      const PerKeyKind kind = perKeyKind(g, key);
      if (kind == PerKeyKind::Param || kind == PerKeyKind::Capture) {
        if (!bound.count(key.spelling.name)) {
          diags_.error("E0410", rule.range, fmt::format("this rule does not bind the key '{}'", key.spelling.name))
              .help(fmt::format("name the event binder '{}' in the position that carries it", key.spelling.name));
        }
      } else if (kind == PerKeyKind::Expression) {  // an invalid key is reported once, as E0412
        std::set<int> reads;
        collectParams(key.expr.get(), reads);
        for (int pi : reads) {
          const std::string& name = g.params[pi].name.name;
          if (bound.count(name)) continue;
          diags_
              .error("E0410", rule.range,
                     fmt::format("this rule does not bind parameter '{}', which the key '{}' reads", name,
                                 key.spelling.name))
              .help(fmt::format("name the event binder '{}' in the position that carries it", name));
        }
      }
    }
  }

 public:
  static std::string factorName(const PersonalDecl& g, const ModelFactor& f) {
    if (!f.label.name.empty()) return f.label.name;
    std::size_t sameKind = 0, position = 0;
    for (const auto& other : g.factors) {
      if (other.label.name.empty() && other.kind.name == f.kind.name) {
        ++sameKind;
        if (&other == &f) position = sameKind;
      }
    }
    return sameKind > 1 ? fmt::format("{}{}", f.kind.name, position) : f.kind.name;
  }

 private:
  DiagnosticEngine& diags_;
};

}  // namespace

PerKeyKind perKeyKind(const PersonalDecl& g, const PerKey& key) {
  if (!key.bareName()) return PerKeyKind::Expression;
  const NameRef& ref = key.expr->ref;
  if (ref.kind == RefKind::Param && ref.decl == &g) return PerKeyKind::Param;
  const std::string& name = key.expr->text;
  if (std::any_of(g.captures.begin(), g.captures.end(), [&](const Ident& c) { return c.name == name; }))
    return PerKeyKind::Capture;
  return ref.kind == RefKind::Unresolved ? PerKeyKind::Invalid : PerKeyKind::Expression;
}

std::vector<int> paramsRead(const Expr* e) {
  std::set<int> s;
  collectParams(e, s);
  return {s.begin(), s.end()};
}

std::string generatorFactorName(const PersonalDecl& g, const ModelFactor& f) { return GenChecker::factorName(g, f); }

bool checkGenerators(const std::vector<std::unique_ptr<Module>>& modules, DiagnosticEngine& diags) {
  const std::size_t before = diags.errorCount();
  GenChecker checker(diags);
  for (const auto& m : modules) {
    for (auto& d : m->decls) {
      if (d->kind == DeclKind::Personal) checker.check(static_cast<PersonalDecl&>(*d));
    }
  }
  return diags.errorCount() == before;
}

}  // namespace cbtl
