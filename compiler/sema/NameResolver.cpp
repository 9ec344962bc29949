#include "compiler/sema/NameResolver.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <map>
#include <set>

namespace cbtl {

std::vector<std::string> GlobalSymbols::valueNames() const {
  std::vector<std::string> out;
  for (const auto& [name, sym] : values) out.push_back(name);
  for (const auto& [name, syms] : enumMembers) out.push_back(name);
  return out;
}

namespace {

const std::vector<std::string>& builtinTypeNames() {
  static const std::vector<std::string> names = {"real", "int", "bool", "text", "vec", "SE2", "SE3", "Conf", "set"};
  return names;
}

// Identifiers that only have meaning as model arguments (threshold direction, text scale and rating).
bool isModelKeyword(const std::string& name) {
  static const std::set<std::string> words = {"above", "below", "relative", "absolute", "digits", "options"};
  return words.count(name) > 0;
}

RefKind refKindOf(const Decl& d) {
  switch (d.kind) {
    case DeclKind::Const:
      return RefKind::Const;
    case DeclKind::Enum:
      return RefKind::EnumType;
    case DeclKind::ItemSet:
      return RefKind::ItemSet;
    case DeclKind::Observe:
      return RefKind::Observation;
    case DeclKind::Var:
      return RefKind::Variable;
    case DeclKind::Function:
      return RefKind::Function;
    case DeclKind::Sampler:
      return RefKind::Sampler;
    case DeclKind::Action:
      return RefKind::Action;
    case DeclKind::Feedback:
      return RefKind::Feedback;
    default:
      return RefKind::Unresolved;
  }
}

class Resolver {
 public:
  Resolver(TypeContext& types, GlobalSymbols& symbols, DiagnosticEngine& diags)
      : types_(types), symbols_(symbols), diags_(diags) {}

  void run(const std::vector<std::unique_ptr<Module>>& modules) {
    for (std::size_t i = 0; i < modules.size(); ++i) declare(*modules[i], i == 0);
    for (const auto& m : modules) resolveModule(*m);
  }

 private:
  // --- pass 1: declare every top-level name -----------------------------------------------------

  void duplicate(const Ident& name, SourceRange previous) {
    diags_.error("E0202", name.range, fmt::format("'{}' is declared more than once", name.name))
        .note("first declared here", previous);
  }

  // All top-level names share one namespace so that a name means one thing wherever it appears.
  bool claim(const Ident& name) {
    auto it = claimed_.find(name.name);
    if (it != claimed_.end()) {
      duplicate(name, it->second);
      return false;
    }
    claimed_.emplace(name.name, name.range);
    return true;
  }

  void declare(Module& module, bool isRoot) {
    for (auto& declPtr : module.decls) {
      Decl& d = *declPtr;
      switch (d.kind) {
        case DeclKind::Domain:
          if (isRoot) symbols_.domainName = d.name.name;
          break;
        case DeclKind::World:
          if (isRoot) symbols_.world = static_cast<const WorldDecl*>(&d);
          break;
        case DeclKind::Import:
          break;
        case DeclKind::Robot:
          if (!d.name.name.empty() && claim(d.name)) symbols_.robots[d.name.name] = &d;
          break;
        case DeclKind::Enum: {
          if (d.name.name.empty() || !claim(d.name)) break;
          symbols_.types[d.name.name] = &d;
          symbols_.values[d.name.name] = Symbol{RefKind::EnumType, &d, -1, d.name.range};
          const auto& e = static_cast<const EnumDecl&>(d);
          std::map<std::string, SourceRange> seen;
          for (std::size_t i = 0; i < e.members.size(); ++i) {
            const Ident& m = e.members[i];
            if (m.name.empty()) continue;
            if (auto it = seen.find(m.name); it != seen.end()) {
              duplicate(m, it->second);
              continue;
            }
            seen.emplace(m.name, m.range);
            symbols_.enumMembers[m.name].push_back(Symbol{RefKind::EnumMember, &d, static_cast<int>(i), m.range});
          }
          break;
        }
        case DeclKind::ItemType:
          if (!d.name.name.empty() && claim(d.name)) symbols_.types[d.name.name] = &d;
          break;
        case DeclKind::Skill:
          if (!d.name.name.empty() && claim(d.name)) symbols_.skills[d.name.name] = static_cast<const SkillDecl*>(&d);
          break;
        case DeclKind::Task:
          if (!d.name.name.empty() && claim(d.name)) symbols_.tasks[d.name.name] = static_cast<const TaskDecl*>(&d);
          break;
        case DeclKind::Personal:
          if (!d.name.name.empty() && claim(d.name)) {
            symbols_.generators[d.name.name] = static_cast<const PersonalDecl*>(&d);
          }
          break;
        case DeclKind::Require:
        case DeclKind::Sample:
        case DeclKind::Cost:
          symbols_.globalScope.push_back(&d);
          if (d.kind == DeclKind::Require && !d.name.name.empty()) claim(d.name);
          break;
        case DeclKind::Var:
          symbols_.globalScope.push_back(&d);
          [[fallthrough]];
        default: {
          if (d.name.name.empty() || !claim(d.name)) break;
          symbols_.values[d.name.name] = Symbol{refKindOf(d), &d, -1, d.name.range};
          break;
        }
      }
    }
  }

  // --- scopes -------------------------------------------------------------------------------

  struct Scope {
    std::map<std::string, Symbol> names;
  };

  void push() { scopes_.emplace_back(); }
  void pop() { scopes_.pop_back(); }

  void bindLocal(const Ident& name, Symbol sym) {
    if (name.name.empty()) return;
    auto& names = scopes_.back().names;
    if (auto it = names.find(name.name); it != names.end()) {
      duplicate(name, it->second.range);
      return;
    }
    sym.range = name.range;
    names.emplace(name.name, sym);
  }

  std::vector<std::string> visibleNames() const {
    std::vector<std::string> out;
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      for (const auto& [n, s] : it->names) out.push_back(n);
    }
    for (auto& n : symbols_.valueNames()) out.push_back(n);
    out.push_back("pi");
    return out;
  }

  // Looks a name up; returns Unresolved (and reports) if it is unknown.
  NameRef lookup(const std::string& name, SourceRange at, bool report = true) {
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      if (auto found = it->names.find(name); found != it->names.end()) {
        return toRef(found->second);
      }
    }
    if (auto it = symbols_.values.find(name); it != symbols_.values.end()) return toRef(it->second);
    if (auto it = symbols_.enumMembers.find(name); it != symbols_.enumMembers.end()) {
      if (it->second.size() == 1) return toRef(it->second.front());
      if (report) {
        Diagnostic& d = diags_.error("E0201", at, fmt::format("'{}' is a member of several enums", name));
        for (const Symbol& s : it->second) {
          d.help(fmt::format("write {}.{}", s.decl->name.name, name));
        }
      }
      return NameRef{};
    }
    if (name == "pi") return NameRef{RefKind::Builtin, nullptr, nullptr, static_cast<int>(BuiltinId::Pi)};
    if (name == "uniform") return NameRef{RefKind::Builtin, nullptr, nullptr, static_cast<int>(BuiltinId::Uniform)};
    if (name == "box") return NameRef{RefKind::Builtin, nullptr, nullptr, static_cast<int>(BuiltinId::Box)};
    if (report && !name.empty()) unknownName(name, at);
    return NameRef{};
  }

  void unknownName(const std::string& name, SourceRange at) {
    Diagnostic& d = diags_.error("E0201", at, fmt::format("unknown name '{}'", name));
    const std::string guess = closestMatch(name, visibleNames());
    if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
    if (symbols_.types.count(name) || symbols_.skills.count(name) || symbols_.tasks.count(name) ||
        symbols_.generators.count(name) || symbols_.robots.count(name)) {
      d.note(fmt::format("'{}' names a type, robot, skill, task or generator, which is not a value", name));
    }
  }

  static NameRef toRef(const Symbol& s) {
    NameRef r;
    r.kind = s.kind;
    r.decl = s.decl;
    r.index = s.index;
    r.binder = s.binder;
    return r;
  }

  // --- types --------------------------------------------------------------------------------

  const Type* resolveType(TypeRef& t) {
    t.resolved = resolveTypeInner(t);
    return t.resolved;
  }

  bool isTypeParam(const std::string& name) const {
    for (const auto& p : typeParams_) {
      if (p == name) return true;
    }
    return false;
  }

  const Type* resolveTypeInner(TypeRef& t) {
    const std::string& n = t.name.name;
    if (n.empty()) return types_.error();
    auto noArgs = [&]() {
      if (!t.args.empty()) {
        diags_.error("E0309", t.range, fmt::format("type '{}' takes no arguments", n));
      }
    };
    auto oneArg = [&]() -> TypeRef::Arg* {
      if (t.args.size() != 1) {
        diags_.error("E0309", t.range,
                     fmt::format("type '{}' takes exactly one argument, as in {}", n,
                                 n == "vec"    ? "vec<3>"
                                 : n == "Conf" ? "Conf<gen3>"
                                               : "set<Book>"));
        return nullptr;
      }
      return &t.args.front();
    };
    if (n == "real") {
      noArgs();
      return types_.real();
    }
    if (n == "int") {
      noArgs();
      return types_.integer();
    }
    if (n == "bool") {
      noArgs();
      return types_.boolean();
    }
    if (n == "text") {
      noArgs();
      return types_.text();
    }
    if (n == "SE2") {
      noArgs();
      return types_.se2();
    }
    if (n == "SE3") {
      noArgs();
      return types_.se3();
    }
    if (n == "vec") {
      TypeRef::Arg* a = oneArg();
      if (a == nullptr) return types_.error();
      if (a->isNumber) {
        if (a->number < 1 || a->number > 64 || a->number != static_cast<int>(a->number)) {
          diags_.error("E0309", a->range, "vec<N> needs a whole number N from 1 to 64");
          return types_.error();
        }
        return types_.vec(static_cast<int>(a->number));
      }
      if (a->type && a->type->args.empty() && isTypeParam(a->type->name.name)) return types_.vecVar(a->type->name.name);
      diags_.error("E0309", a->range, "vec<N> needs a whole number N (or a type parameter in an extern declaration)");
      return types_.error();
    }
    if (n == "Conf") {
      TypeRef::Arg* a = oneArg();
      if (a == nullptr) return types_.error();
      if (!a->isNumber && a->type && a->type->args.empty()) {
        const std::string& r = a->type->name.name;
        if (isTypeParam(r)) return types_.confVar(r);
        if (symbols_.robots.count(r)) return types_.conf(r);
        std::vector<std::string> robots;
        for (const auto& [name, decl] : symbols_.robots) robots.push_back(name);
        Diagnostic& d = diags_.error("E0309", a->range, fmt::format("unknown robot '{}' in Conf<{}>", r, r));
        const std::string guess = closestMatch(r, robots);
        if (!guess.empty())
          d.help(fmt::format("did you mean '{}'?", guess));
        else
          d.help(fmt::format("declare it: robot {} {{ dof: 7; }}  (or import std.kinova for gen3)", r));
        return types_.error();
      }
      diags_.error("E0309", a->range, "Conf<R> needs a robot name");
      return types_.error();
    }
    if (n == "set") {
      TypeRef::Arg* a = oneArg();
      if (a == nullptr) return types_.error();
      if (a->isNumber || !a->type) {
        diags_.error("E0309", a->range, "set<T> needs an element type");
        return types_.error();
      }
      const Type* e = resolveType(*a->type);
      return e->isError() ? e : types_.setOf(e);
    }
    if (auto it = symbols_.types.find(n); it != symbols_.types.end()) {
      noArgs();
      if (it->second->kind == DeclKind::Enum) return types_.enumType(static_cast<const EnumDecl*>(it->second), n);
      return types_.itemType(static_cast<const ItemTypeDecl*>(it->second), n);
    }
    Diagnostic& d = diags_.error("E0206", t.name.range, fmt::format("unknown type '{}'", n));
    std::vector<std::string> candidates = builtinTypeNames();
    for (const auto& [name, decl] : symbols_.types) candidates.push_back(name);
    const std::string guess = closestMatch(n, candidates);
    if (!guess.empty())
      d.help(fmt::format("did you mean '{}'?", guess));
    else if (symbols_.values.count(n))
      d.note(fmt::format("'{}' is a value, not a type", n));
    return types_.error();
  }

  // --- expressions --------------------------------------------------------------------------

  void resolveArgs(std::vector<Arg>& args) {
    for (auto& a : args) resolveExpr(a.value.get());
  }

  void resolveBinder(Binder& b) {
    resolveExpr(b.set.get());
    for (auto& bd : b.names) {
      Symbol s;
      s.kind = RefKind::Binder;
      s.binder = bd.get();
      bindLocal(bd->name, s);
    }
  }

  void resolveExpr(Expr* e) {
    if (e == nullptr) return;
    switch (e->kind) {
      case ExprKind::Name: {
        e->ref = lookupWithBinders(e->text, e->range);
        return;
      }
      case ExprKind::Member: {
        Expr* object = e->operands[0].get();
        if (object->kind == ExprKind::Name) {
          // Enum.member and itemSet.entry are qualified names, not field accesses.
          NameRef base = lookupWithBinders(object->text, object->range, /*report=*/false);
          if (base.kind == RefKind::EnumType) {
            object->ref = base;
            const auto* en = static_cast<const EnumDecl*>(base.decl);
            for (std::size_t i = 0; i < en->members.size(); ++i) {
              if (en->members[i].name == e->text) {
                e->ref = NameRef{RefKind::EnumMember, en, nullptr, static_cast<int>(i)};
                return;
              }
            }
            std::vector<std::string> names;
            for (const auto& m : en->members) names.push_back(m.name);
            Diagnostic& d = diags_.error("E0208", e->nameRange,
                                         fmt::format("enum '{}' has no member '{}'", en->name.name, e->text));
            const std::string guess = closestMatch(e->text, names);
            if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
            return;
          }
          if (base.kind == RefKind::ItemSet) {
            object->ref = base;
            const auto* items = static_cast<const ItemsDecl*>(base.decl);
            for (std::size_t i = 0; i < items->entries.size(); ++i) {
              if (items->entries[i].name.name == e->text) {
                e->ref = NameRef{RefKind::ItemEntry, items, nullptr, static_cast<int>(i)};
                return;
              }
            }
            // Not an entry: fall through to field access on the set (reported by the type checker).
          }
        }
        resolveExpr(object);
        return;
      }
      case ExprKind::Call: {
        Expr* callee = e->operands[0].get();
        if (callee->kind == ExprKind::Name) {
          callee->ref = lookupWithBinders(callee->text, callee->range);
          e->ref = callee->ref;
        } else {
          resolveExpr(callee);
        }
        resolveArgs(e->args);
        return;
      }
      case ExprKind::Quantifier: {
        push();
        resolveBinder(*e->binder);
        resolveExpr(e->operands[0].get());
        resolveExpr(e->operands[1].get());
        pop();
        return;
      }
      default:
        for (auto& op : e->operands) resolveExpr(op.get());
        return;
    }
  }

  NameRef lookupWithBinders(const std::string& name, SourceRange at, bool report = true) {
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      auto found = it->names.find(name);
      if (found == it->names.end()) continue;
      return toRef(found->second);
    }
    return lookup(name, at, report);
  }

  // --- declarations -------------------------------------------------------------------------

  void resolveIndex(IndexSpec* index) {
    if (index == nullptr) return;
    resolveExpr(index->set.get());
  }

  void resolveScopeStmt(Decl& d) {
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
  void bindBodyVariables(const std::vector<std::unique_ptr<Decl>>& body) {
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

  void resolveActions(std::vector<std::unique_ptr<ActionStmt>>& stmts) {
    for (auto& s : stmts) {
      switch (s->kind) {
        case ActionStmtKind::Call: {
          s->calleeRef = lookup(s->callee.name, s->callee.range, false);
          if (s->calleeRef.kind != RefKind::Action) {
            Diagnostic& d =
                diags_.error("E0503", s->callee.range, fmt::format("'{}' is not an action", s->callee.name));
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
      }
    }
  }

  void resolveCallable(CallableDecl& c) {
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

  void resolvePersonal(PersonalDecl& g) {
    for (auto& p : g.params) resolveType(p.type);
    push();
    for (std::size_t i = 0; i < g.params.size(); ++i) {
      bindLocal(g.params[i].name, Symbol{RefKind::Param, &g, static_cast<int>(i), g.params[i].name.range});
    }
    for (auto& f : g.factors) {
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
    for (auto& a : g.accepts) resolveExpr(a.get());
    for (auto& f : g.fallbacks) resolveExpr(f.get());
    for (auto& c : g.guards) resolveExpr(c.get());
    for (auto& rule : g.learnRules) {
      rule.eventRef = lookup(rule.event.name, rule.event.range, false);
      if (rule.eventRef.kind != RefKind::Feedback) {
        Diagnostic& d = diags_.error("E0210", rule.event.range,
                                     fmt::format("'{}' is not a declared feedback event", rule.event.name));
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
    pop();
  }

  void resolveSkill(SkillDecl& s) {
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

  void resolveTask(TaskDecl& t) {
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

  void resolveModule(Module& module) {
    const Decl* firstDomain = nullptr;
    bool first = true;
    for (auto& declPtr : module.decls) {
      Decl& d = *declPtr;
      if (d.kind == DeclKind::Domain) {
        if (firstDomain != nullptr) {
          diags_.error("E0211", d.range, "a file has at most one domain header")
              .note("the header is here", firstDomain->range);
        } else if (!first) {
          diags_.error("E0211", d.range, "the domain header must be the first declaration of the file");
        }
        if (firstDomain == nullptr) firstDomain = &d;
      }
      first = false;
      switch (d.kind) {
        case DeclKind::Robot:
          for (auto& f : static_cast<RobotDecl&>(d).fields) resolveExpr(f.value.get());
          break;
        case DeclKind::Const: {
          auto& c = static_cast<ConstDecl&>(d);
          resolveIndex(c.index.get());
          if (c.type) resolveType(*c.type);
          resolveExpr(c.value.get());
          break;
        }
        case DeclKind::ItemType:
          for (auto& f : static_cast<ItemTypeDecl&>(d).fields) resolveType(f.type);
          break;
        case DeclKind::ItemSet: {
          auto& items = static_cast<ItemsDecl&>(d);
          resolveType(items.itemType);
          for (auto& e : items.entries) {
            for (auto& f : e.fields) resolveExpr(f.value.get());
          }
          break;
        }
        case DeclKind::Observe: {
          auto& o = static_cast<ObserveDecl&>(d);
          resolveIndex(o.index.get());
          resolveType(o.type);
          break;
        }
        case DeclKind::Feedback:
          for (auto& p : static_cast<FeedbackDecl&>(d).params) resolveType(p.type);
          break;
        case DeclKind::Function:
        case DeclKind::Sampler:
        case DeclKind::Action:
          resolveCallable(static_cast<CallableDecl&>(d));
          break;
        case DeclKind::Var:
        case DeclKind::Require:
        case DeclKind::Sample:
        case DeclKind::Cost:
          resolveScopeStmt(d);
          break;
        case DeclKind::Personal:
          resolvePersonal(static_cast<PersonalDecl&>(d));
          break;
        case DeclKind::Skill:
          resolveSkill(static_cast<SkillDecl&>(d));
          break;
        case DeclKind::Task:
          resolveTask(static_cast<TaskDecl&>(d));
          break;
        default:
          break;
      }
    }
  }

  TypeContext& types_;
  GlobalSymbols& symbols_;
  DiagnosticEngine& diags_;
  std::map<std::string, SourceRange> claimed_;
  std::vector<Scope> scopes_;
  std::vector<std::string> typeParams_;
};

}  // namespace

bool resolveNames(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, GlobalSymbols& symbols,
                  DiagnosticEngine& diags) {
  const std::size_t before = diags.errorCount();
  Resolver(types, symbols, diags).run(modules);
  return diags.errorCount() == before;
}

}  // namespace cbtl
