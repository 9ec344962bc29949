// Personalization.h — applying generators' initiation patterns to a task's variables.
//
// For a generator of arity m, every m-tuple of distinct task variables whose names match the parameters'
// patterns (globs with captures that must agree across parameters, or regexes) and whose types equal the
// parameters' types yields one personalized constraint instance. Instances of one generator share its
// learned models; which model an instance reads is chosen by the generator's `per` keys (captures, or the
// value of a parameter at evaluation time). The same generator applies to every task where it matches.
#pragma once

#include "runtime/core/Program.h"

#include <optional>
#include <string>
#include <vector>

namespace cbtl::rt {

struct ModelKeyPart {
  bool fromValue = false;  // true: the value of a parameter (node), rendered; false: fixed text
  std::uint32_t node = 0;
  ValueType type;
  std::string text;
};

struct PersonalInstance {
  std::uint32_t generator = 0;            // index into Program::generators()
  std::string name;                       // "gen(var, var, ...)"
  std::vector<ir::VarId> vars;            // one per parameter
  std::vector<ir::VarId> hyperedge;       // sorted, unique
  std::vector<std::string> captures;      // one per generator capture
  std::optional<std::uint32_t> guard;     // node; false: the constraint does not apply
  std::vector<std::uint32_t> features;    // per factor: feature node over the instance's variables, or UINT32_MAX
  std::vector<ValueType> featureTypes;    // per factor (tables render the feature's value as their key)
  std::vector<CompiledContext> contexts;  // per factor: a text factor's context over the instance's variables
  std::vector<ModelKeyPart> key;
};

// All instances for a task, in a deterministic order (generators in declaration order, then tuples in the
// order of the task's variables). Throws RuntimeError for a malformed pattern.
std::vector<PersonalInstance> personalize(Program& program, const ir::Task& task);

}  // namespace cbtl::rt
