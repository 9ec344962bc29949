// The `resolve-names` entry point, pass 1 (every top-level name of every module is declared in one
// namespace) and the pass-2 dispatch over each module's declarations; the other concerns of the resolver
// are implemented in the NameResolver*.cpp files listed in NameResolverInternal.h.
#include "compiler/sema/NameResolver.h"

#include "compiler/sema/NameResolverInternal.h"

#include <fmt/format.h>

namespace cbtl {

std::vector<std::string> GlobalSymbols::valueNames() const {
  std::vector<std::string> out;
  for (const auto& [name, sym] : values) out.push_back(name);
  for (const auto& [name, syms] : enumMembers) out.push_back(name);
  return out;
}

bool resolveNames(const std::vector<std::unique_ptr<Module>>& modules, TypeContext& types, GlobalSymbols& symbols,
                  DiagnosticEngine& diags) {
  const std::size_t before = diags.errorCount();
  detail::NameResolver(types, symbols, diags).run(modules);
  return diags.errorCount() == before;
}

namespace detail {
namespace {

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

}  // namespace

void NameResolver::run(const std::vector<std::unique_ptr<Module>>& modules) {
  for (std::size_t i = 0; i < modules.size(); ++i) declare(*modules[i], i == 0);
  for (const auto& m : modules) resolveModule(*m);
}

void NameResolver::duplicate(const Ident& name, SourceRange previous) {
  diags_.error("E0202", name.range, fmt::format("'{}' is declared more than once", name.name))
      .note("first declared here", previous);
}

// All top-level names share one namespace so that a name means one thing wherever it appears.
bool NameResolver::claim(const Ident& name) {
  auto it = claimed_.find(name.name);
  if (it != claimed_.end()) {
    duplicate(name, it->second);
    return false;
  }
  claimed_.emplace(name.name, name.range);
  return true;
}

void NameResolver::declare(Module& module, bool isRoot) {
  for (auto& declPtr : module.decls) {
    Decl& d = *declPtr;
    switch (d.kind) {
      case DeclKind::Domain:
        if (isRoot) symbols_.domainName = d.name.name;
        break;
      case DeclKind::World:
        if (isRoot) symbols_.world = static_cast<const WorldDecl*>(&d);
        break;
      case DeclKind::Simulator:
        if (isRoot) symbols_.simulator = static_cast<const SimulatorDecl*>(&d);
        break;
      case DeclKind::Import:
        break;
      case DeclKind::Robot:
        if (!d.name.name.empty() && claim(d.name)) symbols_.robots[d.name.name] = &d;
        break;
      case DeclKind::Clearance:
        if (!d.name.name.empty() && claim(d.name))
          symbols_.clearances[d.name.name] = static_cast<const ClearanceDecl*>(&d);
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

void NameResolver::resolveModule(Module& module) {
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

}  // namespace detail
}  // namespace cbtl
