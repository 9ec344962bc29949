// Type.h — semantic types of .cbtl expressions and variables, interned in a TypeContext.
//
// Types are immutable and interned, so two types are equal exactly when their pointers are equal.
// Generic extern declarations use type variables: vec<N> with a size variable and Conf<R> with a robot
// variable; calls bind them by unification (Unifier).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cbtl {

struct EnumDecl;
struct ItemTypeDecl;

enum class TypeKind { Error, Real, Int, Bool, Text, Enum, Item, Vec, SE2, SE3, Conf, Set, Tuple, Range, Void };

struct Type {
  TypeKind kind = TypeKind::Error;
  const EnumDecl* enumDecl = nullptr;      // Enum
  const ItemTypeDecl* itemDecl = nullptr;  // Item
  int size = 0;                            // Vec (0 when sizeVar is set)
  std::string sizeVar;                     // Vec<N> in a generic signature
  std::string robot;                       // Conf (empty when robotVar is set)
  std::string robotVar;                    // Conf<R> in a generic signature
  const Type* element = nullptr;           // Set, Range
  std::vector<const Type*> elements;       // Tuple
  std::string spelling;                    // canonical text: "vec<3>", "set<Book>", ...

  bool isError() const { return kind == TypeKind::Error; }
  bool isNumeric() const { return kind == TypeKind::Real || kind == TypeKind::Int; }
  // Types a CSP variable may have (and so a generator parameter).
  bool isVariableType() const;
  // Discrete types usable as table keys and `per` keys.
  bool isDiscrete() const;
  bool isGeneric() const;
};

class TypeContext {
 public:
  const Type* error();
  const Type* real();
  const Type* integer();
  const Type* boolean();
  const Type* text();
  const Type* voidType();
  const Type* se2();
  const Type* se3();
  const Type* enumType(const EnumDecl* decl, const std::string& name);
  const Type* itemType(const ItemTypeDecl* decl, const std::string& name);
  const Type* vec(int size);
  const Type* vecVar(const std::string& sizeVar);
  const Type* conf(const std::string& robot);
  const Type* confVar(const std::string& robotVar);
  const Type* setOf(const Type* element);
  const Type* rangeOf(const Type* element);
  const Type* tuple(std::vector<const Type*> elements);

 private:
  const Type* intern(Type t);
  std::map<std::string, std::unique_ptr<Type>> types_;
};

// Binds the type variables of a generic signature while checking one call.
class Unifier {
 public:
  explicit Unifier(TypeContext& types) : types_(types) {}
  // True if `actual` can be passed where `formal` is expected (int widens to real), binding variables.
  bool unify(const Type* formal, const Type* actual);
  // `formal` with bound variables replaced.
  const Type* substitute(const Type* formal);

 private:
  TypeContext& types_;
  std::map<std::string, int> sizes_;
  std::map<std::string, std::string> robots_;
};

// True if a value of type `from` may be used where `to` is expected (identity, int -> real).
bool assignable(const Type* to, const Type* from);

}  // namespace cbtl
