// Symbols.h — the global symbol table of a translation unit: every top-level name of the root file and
// its imports in one flat namespace, plus enum members (which may be used bare when unambiguous).
#pragma once

#include "compiler/ast/Ast.h"

#include <map>
#include <string>
#include <vector>

namespace cbtl {

struct Symbol {
  RefKind kind = RefKind::Unresolved;
  const Decl* decl = nullptr;
  int index = -1;
  SourceRange range;                   // where the name is declared
  const BinderDecl* binder = nullptr;  // RefKind::Binder
};

// Kinds of top-level declarations that are not values: they live in their own tables.
struct GlobalSymbols {
  std::map<std::string, Symbol> values;      // consts, vars, observations, functions, ...
  std::map<std::string, const Decl*> types;  // enum and item type declarations
  std::map<std::string, const Decl*> robots;
  std::map<std::string, const SkillDecl*> skills;
  std::map<std::string, const TaskDecl*> tasks;
  std::map<std::string, const PersonalDecl*> generators;
  std::map<std::string, const ClearanceDecl*> clearances;  // named only by `allow` targets
  std::map<std::string, std::vector<Symbol>> enumMembers;  // bare member name -> every enum that has it
  std::vector<const Decl*> globalScope;                    // top-level var/require/sample/cost, in order
  const WorldDecl* world = nullptr;
  const SimulatorDecl* simulator = nullptr;
  std::string domainName;

  // Every value name, for did-you-mean suggestions.
  std::vector<std::string> valueNames() const;
};

// Built-in names the compiler knows without a declaration.
enum class BuiltinId { Pi = 0, Uniform = 1, Box = 2 };

}  // namespace cbtl
