// resolve-names: types as written (TypeRef) to semantic types. Built-in types with their arguments
// (vec<N>, Conf<R>, set<T>), type parameters of extern signatures, and enum and item types by name.
#include "compiler/sema/NameResolverInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

namespace cbtl::detail {
namespace {

const std::vector<std::string>& builtinTypeNames() {
  static const std::vector<std::string> names = {"real", "int", "bool", "text", "vec", "SE2", "SE3", "Conf", "set"};
  return names;
}

}  // namespace

const Type* NameResolver::resolveType(TypeRef& t) {
  t.resolved = resolveTypeInner(t);
  return t.resolved;
}

bool NameResolver::isTypeParam(const std::string& name) const {
  for (const auto& p : typeParams_) {
    if (p == name) return true;
  }
  return false;
}

const Type* NameResolver::resolveTypeInner(TypeRef& t) {
  const std::string& n = t.name.name;
  if (n.empty()) return types_.error();
  if (n == "real") {
    checkNoTypeArgs(t);
    return types_.real();
  }
  if (n == "int") {
    checkNoTypeArgs(t);
    return types_.integer();
  }
  if (n == "bool") {
    checkNoTypeArgs(t);
    return types_.boolean();
  }
  if (n == "text") {
    checkNoTypeArgs(t);
    return types_.text();
  }
  if (n == "SE2") {
    checkNoTypeArgs(t);
    return types_.se2();
  }
  if (n == "SE3") {
    checkNoTypeArgs(t);
    return types_.se3();
  }
  if (n == "vec") return vecType(t);
  if (n == "Conf") return confType(t);
  if (n == "set") return setType(t);
  if (auto it = symbols_.types.find(n); it != symbols_.types.end()) {
    checkNoTypeArgs(t);
    if (it->second->kind == DeclKind::Enum) return types_.enumType(static_cast<const EnumDecl*>(it->second), n);
    return types_.itemType(static_cast<const ItemTypeDecl*>(it->second), n);
  }
  return unknownType(t);
}

void NameResolver::checkNoTypeArgs(const TypeRef& t) {
  if (!t.args.empty()) {
    diags_.error("E0309", t.range, fmt::format("type '{}' takes no arguments", t.name.name));
  }
}

TypeRef::Arg* NameResolver::singleTypeArg(TypeRef& t) {
  const std::string& n = t.name.name;
  if (t.args.size() != 1) {
    diags_.error("E0309", t.range,
                 fmt::format("type '{}' takes exactly one argument, as in {}", n,
                             n == "vec"    ? "vec<3>"
                             : n == "Conf" ? "Conf<gen3>"
                                           : "set<Book>"));
    return nullptr;
  }
  return &t.args.front();
}

// vec<N> with a whole N from 1 to 64, or vec<N> with a type parameter N in an extern signature.
const Type* NameResolver::vecType(TypeRef& t) {
  TypeRef::Arg* a = singleTypeArg(t);
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

// Conf<R> with a declared robot R, or with a type parameter R in an extern signature.
const Type* NameResolver::confType(TypeRef& t) {
  TypeRef::Arg* a = singleTypeArg(t);
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

const Type* NameResolver::setType(TypeRef& t) {
  TypeRef::Arg* a = singleTypeArg(t);
  if (a == nullptr) return types_.error();
  if (a->isNumber || !a->type) {
    diags_.error("E0309", a->range, "set<T> needs an element type");
    return types_.error();
  }
  const Type* e = resolveType(*a->type);
  return e->isError() ? e : types_.setOf(e);
}

// E0206 with the closest built-in or declared type name, or a note when the name is a value.
const Type* NameResolver::unknownType(TypeRef& t) {
  const std::string& n = t.name.name;
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

}  // namespace cbtl::detail
