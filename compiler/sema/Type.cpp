#include "compiler/sema/Type.h"

#include <fmt/format.h>

namespace cbtl {

bool Type::isVariableType() const {
  switch (kind) {
    case TypeKind::Real:
    case TypeKind::Int:
    case TypeKind::Bool:
    case TypeKind::Text:
    case TypeKind::Enum:
    case TypeKind::Item:
    case TypeKind::Vec:
    case TypeKind::SE2:
    case TypeKind::SE3:
    case TypeKind::Conf:
      return true;
    default:
      return false;
  }
}

bool Type::isDiscrete() const {
  switch (kind) {
    case TypeKind::Int:
    case TypeKind::Bool:
    case TypeKind::Text:
    case TypeKind::Enum:
    case TypeKind::Item:
      return true;
    default:
      return false;
  }
}

bool Type::isGeneric() const {
  if (!sizeVar.empty() || !robotVar.empty()) return true;
  if (element != nullptr && element->isGeneric()) return true;
  for (const Type* e : elements) {
    if (e->isGeneric()) return true;
  }
  return false;
}

const Type* TypeContext::intern(Type t) {
  auto it = types_.find(t.spelling);
  if (it != types_.end()) return it->second.get();
  auto owned = std::make_unique<Type>(std::move(t));
  const Type* raw = owned.get();
  types_.emplace(raw->spelling, std::move(owned));
  return raw;
}

namespace {
Type simple(TypeKind kind, const char* spelling) {
  Type t;
  t.kind = kind;
  t.spelling = spelling;
  return t;
}
}  // namespace

const Type* TypeContext::error() { return intern(simple(TypeKind::Error, "<error>")); }
const Type* TypeContext::real() { return intern(simple(TypeKind::Real, "real")); }
const Type* TypeContext::integer() { return intern(simple(TypeKind::Int, "int")); }
const Type* TypeContext::boolean() { return intern(simple(TypeKind::Bool, "bool")); }
const Type* TypeContext::text() { return intern(simple(TypeKind::Text, "text")); }
const Type* TypeContext::voidType() { return intern(simple(TypeKind::Void, "void")); }
const Type* TypeContext::se2() { return intern(simple(TypeKind::SE2, "SE2")); }
const Type* TypeContext::se3() { return intern(simple(TypeKind::SE3, "SE3")); }

const Type* TypeContext::enumType(const EnumDecl* decl, const std::string& name) {
  Type t;
  t.kind = TypeKind::Enum;
  t.enumDecl = decl;
  t.spelling = name;
  return intern(std::move(t));
}

const Type* TypeContext::itemType(const ItemTypeDecl* decl, const std::string& name) {
  Type t;
  t.kind = TypeKind::Item;
  t.itemDecl = decl;
  t.spelling = name;
  return intern(std::move(t));
}

const Type* TypeContext::vec(int size) {
  Type t;
  t.kind = TypeKind::Vec;
  t.size = size;
  t.spelling = fmt::format("vec<{}>", size);
  return intern(std::move(t));
}

const Type* TypeContext::vecVar(const std::string& sizeVar) {
  Type t;
  t.kind = TypeKind::Vec;
  t.sizeVar = sizeVar;
  t.spelling = fmt::format("vec<{}>", sizeVar);
  return intern(std::move(t));
}

const Type* TypeContext::conf(const std::string& robot) {
  Type t;
  t.kind = TypeKind::Conf;
  t.robot = robot;
  t.spelling = fmt::format("Conf<{}>", robot);
  return intern(std::move(t));
}

const Type* TypeContext::confVar(const std::string& robotVar) {
  Type t;
  t.kind = TypeKind::Conf;
  t.robotVar = robotVar;
  // A distinct spelling from a robot of the same name: type variables live in signatures only.
  t.spelling = fmt::format("Conf<{}?>", robotVar);
  return intern(std::move(t));
}

const Type* TypeContext::setOf(const Type* element) {
  Type t;
  t.kind = TypeKind::Set;
  t.element = element;
  t.spelling = fmt::format("set<{}>", element->spelling);
  return intern(std::move(t));
}

const Type* TypeContext::rangeOf(const Type* element) {
  Type t;
  t.kind = TypeKind::Range;
  t.element = element;
  t.spelling = fmt::format("range<{}>", element->spelling);
  return intern(std::move(t));
}

const Type* TypeContext::tuple(std::vector<const Type*> elements) {
  Type t;
  t.kind = TypeKind::Tuple;
  t.spelling = "(";
  for (std::size_t i = 0; i < elements.size(); ++i) t.spelling += (i ? ", " : "") + elements[i]->spelling;
  t.spelling += ")";
  t.elements = std::move(elements);
  return intern(std::move(t));
}

bool assignable(const Type* to, const Type* from) {
  if (to == from) return true;
  if (to->isError() || from->isError()) return true;  // an error was already reported
  if (to->kind == TypeKind::Real && from->kind == TypeKind::Int) return true;
  if (to->kind == TypeKind::Set && from->kind == TypeKind::Set) return assignable(to->element, from->element);
  if (to->kind == TypeKind::Range && from->kind == TypeKind::Range) return assignable(to->element, from->element);
  return false;
}

bool Unifier::unify(const Type* formal, const Type* actual) {
  if (formal->isError() || actual->isError()) return true;
  if (formal->kind == TypeKind::Vec && !formal->sizeVar.empty()) {
    if (actual->kind != TypeKind::Vec || actual->size == 0) return false;
    auto [it, inserted] = sizes_.emplace(formal->sizeVar, actual->size);
    return inserted || it->second == actual->size;
  }
  if (formal->kind == TypeKind::Conf && !formal->robotVar.empty()) {
    if (actual->kind != TypeKind::Conf || actual->robot.empty()) return false;
    auto [it, inserted] = robots_.emplace(formal->robotVar, actual->robot);
    return inserted || it->second == actual->robot;
  }
  if ((formal->kind == TypeKind::Set || formal->kind == TypeKind::Range) && formal->kind == actual->kind) {
    return unify(formal->element, actual->element);
  }
  if (formal->kind == TypeKind::Tuple && actual->kind == TypeKind::Tuple) {
    if (formal->elements.size() != actual->elements.size()) return false;
    for (std::size_t i = 0; i < formal->elements.size(); ++i) {
      if (!unify(formal->elements[i], actual->elements[i])) return false;
    }
    return true;
  }
  return assignable(formal, actual);
}

const Type* Unifier::substitute(const Type* formal) {
  if (formal->kind == TypeKind::Vec && !formal->sizeVar.empty()) {
    auto it = sizes_.find(formal->sizeVar);
    return it == sizes_.end() ? formal : types_.vec(it->second);
  }
  if (formal->kind == TypeKind::Conf && !formal->robotVar.empty()) {
    auto it = robots_.find(formal->robotVar);
    return it == robots_.end() ? formal : types_.conf(it->second);
  }
  if (formal->kind == TypeKind::Set) return types_.setOf(substitute(formal->element));
  if (formal->kind == TypeKind::Range) return types_.rangeOf(substitute(formal->element));
  if (formal->kind == TypeKind::Tuple) {
    std::vector<const Type*> elems;
    for (const Type* e : formal->elements) elems.push_back(substitute(e));
    return types_.tuple(std::move(elems));
  }
  return formal;
}

}  // namespace cbtl
