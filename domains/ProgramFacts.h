// ProgramFacts.h — what a domain simulator learns from the loaded program instead of compiling it in: the scene
// of the program's `world "..."` line (its path and, when the caller has loaded it already, the loaded scene) and
// the program's item sets (`items name : Type { ... }`, e.g. the Books catalogue), and its number constants
// (`const name = 0.30;`, e.g. Feeding's plate area on the table).
//
// The program is the single source of these facts: the app fills them from what it compiled and bound
// (app/SimulatorFacts.h), tests from the domain's .cbtl file or an explicit scene path. A robot domain's
// simulator throws std::invalid_argument when the facts name no scene (a configuration error, not a crash;
// home::programScene, domains/home/HomeScene.h).
#pragma once

#include "ir/ConstraintGraph.h"
#include "runtime/core/Values.h"  // rt::RuntimeError

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::world {
class Scene;
}

namespace cbtl::domains {

struct ProgramFacts {
  std::string scenePath;                      // the program's scene file, resolved; empty: the program has none
  std::shared_ptr<const world::Scene> scene;  // that file, loaded and shared read-only; null: load scenePath
  std::vector<ir::Clearance> clearances;      // the program's clearances (scenePath is loaded with them)
  std::vector<ir::ItemSet> itemSets;          // the program's item sets, in declaration order
  // The program's constants whose value is a number as written (a literal, or a negated one), by name.
  struct Number {
    double value = 0;
    ir::Span span;  // the declaration
  };
  std::map<std::string, Number> numbers;
};

// The program's item set of entries of `itemType` that comes first (the one Program::render names values by);
// null when there is none.
inline const ir::ItemSet* firstItemSetOfType(const ProgramFacts& facts, std::string_view itemType) {
  for (const ir::ItemSet& set : facts.itemSets)
    if (set.itemType == itemType) return &set;
  return nullptr;
}

// Number constant `name` of the program; throws rt::RuntimeError (bad input: a program that does not fit its
// simulator) naming it and what it is for (`purpose`) when the program declares none.
inline const ProgramFacts::Number& requireNumber(const ProgramFacts& facts, const std::string& name,
                                                 std::string_view purpose) {
  const auto it = facts.numbers.find(name);
  if (it == facts.numbers.end())
    throw rt::RuntimeError("", "the program declares no number constant '" + name + "' (" + std::string(purpose) + ")");
  return it->second;
}

// "file:line:col" of a declaration, as rt::RuntimeError's `where`.
inline std::string whereOf(const ir::Span& span) {
  if (span.file.empty()) return {};
  return span.file + ":" + std::to_string(span.line) + ":" + std::to_string(span.column);
}

}  // namespace cbtl::domains
