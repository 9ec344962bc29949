// resolve-names: local scopes and name lookup. Innermost scope first, then the global namespace, then
// unambiguous enum members, then the built-ins; unknown names get the closest visible name as a suggestion.
#include "compiler/sema/NameResolverInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <cctype>

namespace cbtl::detail {

void NameResolver::bindLocal(const Ident& name, Symbol sym) {
  if (name.name.empty()) return;
  auto& names = scopes_.back().names;
  if (auto it = names.find(name.name); it != names.end()) {
    duplicate(name, it->second.range);
    return;
  }
  sym.range = name.range;
  names.emplace(name.name, sym);
}

std::vector<std::string> NameResolver::visibleNames() const {
  std::vector<std::string> out;
  for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
    for (const auto& [n, s] : it->names) out.push_back(n);
  }
  for (auto& n : symbols_.valueNames()) out.push_back(n);
  out.push_back("pi");
  return out;
}

NameRef NameResolver::lookup(const std::string& name, SourceRange at, bool report) {
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

NameRef NameResolver::lookupWithBinders(const std::string& name, SourceRange at, bool report) {
  for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
    auto found = it->names.find(name);
    if (found == it->names.end()) continue;
    return toRef(found->second);
  }
  return lookup(name, at, report);
}

void NameResolver::unknownName(const std::string& name, SourceRange at) {
  Diagnostic& d = diags_.error("E0201", at, fmt::format("unknown name '{}'", name));
  const std::string guess = closestMatch(name, visibleNames());
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "true" || lower == "false") {
    // Python's and C#'s spellings: the literals are keywords, so no visible name is near them.
    d.help(fmt::format("booleans are written in lower case: '{}'", lower));
  } else if (!guess.empty()) {
    d.help(fmt::format("did you mean '{}'?", guess));
  }
  if (symbols_.types.count(name) || symbols_.skills.count(name) || symbols_.tasks.count(name) ||
      symbols_.generators.count(name) || symbols_.robots.count(name)) {
    d.note(fmt::format("'{}' names a type, robot, skill, task or generator, which is not a value", name));
  }
  if (symbols_.clearances.count(name)) {
    d.note(fmt::format("'{}' is a clearance, a class of scene bodies: only the target of an 'allow' names it", name));
  }
}

NameRef NameResolver::toRef(const Symbol& s) {
  NameRef r;
  r.kind = s.kind;
  r.decl = s.decl;
  r.index = s.index;
  r.binder = s.binder;
  return r;
}

}  // namespace cbtl::detail
