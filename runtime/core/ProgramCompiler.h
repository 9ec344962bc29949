// ProgramCompiler.h — turns IR expressions (ir::Expr trees) into nodes of a Program's ExprPool.
//
// The one place that reads an expression's Op: a switch over it picks the pool node (or the table of
// constants, variable offsets or observation offsets) that evaluates it. Program's constructor compiles every
// declaration of its graph with one (initial values, constraints, domain checks, samplers, generators,
// costs); personalization (generator instances) and action plans use one for what they compile later.
//
// Compiling appends nodes to the program's pool and grows its frameSize(); the program's layout and type
// facts are only read. Not thread-safe: finish compiling before solvers share the program.
#pragma once

#include "runtime/core/Program.h"

#include "ir/ConstraintGraph.h"

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::rt {

class ProgramCompiler {
 public:
  // What names in an expression refer to. `params` maps a generator (or inlined function) parameter index to
  // a node that yields it (instance variables or frame reads; UINT32_MAX: not bound here); `locals` maps
  // binder names to frame offsets (extended as binders appear).
  struct Scope {
    std::vector<std::uint32_t> params;
    std::map<std::string, std::uint32_t> locals;
    std::uint32_t* frameTop = nullptr;  // next free frame slot; binders allocate from here
  };

  explicit ProgramCompiler(Program& program) : program_(program) {}

  // Errors are reported at `span` (the declaration being compiled) until the next call; null: no location.
  void locateAt(const ir::Span* span) { span_ = span; }

  // The root node of `e`. Throws RuntimeError (located) for what the runtime cannot execute, a value wider
  // than kMaxValueWidth or a call whose arguments exceed kMaxCallArgsWidth.
  std::uint32_t compile(const ir::Expr& e, Scope& scope);

  // A constant expression evaluated now: its value (at least one double).
  std::vector<double> constantValue(const ir::Expr& e);
  // A constant as the strings a text-preference model is shown: one per member for a set, otherwise the
  // rendered value.
  std::vector<std::string> constantStrings(const ir::Expr& e);
  // The member values of a set expression (enum, item set, constant list) and their type.
  std::vector<double> setMembers(const ir::Expr& set, ValueType& elem, Scope& scope);

  // The declarations of the program's graph, in the order Program's constructor compiles them.
  std::vector<std::pair<ir::VarId, std::uint32_t>> compileInitialValues();  // variable, its `= init` node
  std::vector<CompiledConstraint> compileConstraints();
  std::vector<DomainCheck> compileDomainChecks();
  std::vector<CompiledSampler> compileSamplers();
  std::vector<CompiledGenerator> compileGenerators();
  std::vector<std::uint32_t> compileCosts();  // maximized costs negated

 private:
  std::string at() const;  // the current location, or empty
  double memberIndex(const std::string& typeName, const std::string& member) const;
  std::uint32_t constNode(std::vector<double> values, std::uint16_t width);
  std::uint32_t compileNode(const ir::Expr& e, Scope& scope);
  std::uint32_t compileVar(const ir::Expr& e);
  std::uint32_t compileParam(const ir::Expr& e, Scope& scope);
  std::uint32_t compileLocal(const ir::Expr& e, Scope& scope);
  std::uint32_t compileConstRef(const ir::Expr& e, Scope& scope);
  std::uint32_t compileObservation(const ir::Expr& e, Scope& scope);
  std::uint32_t compileFamily(const ir::Expr& e, Scope& scope);
  std::uint32_t compileMember(const ir::Expr& e, Scope& scope);
  std::uint32_t compileUnary(const ir::Expr& e, Scope& scope);
  std::uint32_t compileBinary(const ir::Expr& e, Scope& scope);
  std::uint32_t compileIf(const ir::Expr& e, Scope& scope);
  std::uint32_t compileTuple(const ir::Expr& e, Scope& scope);
  std::uint32_t compileCall(const ir::Expr& e, Scope& scope);
  std::uint32_t compileQuantifier(const ir::Expr& e, Scope& scope, std::size_t binder);
  std::uint32_t compileIn(const ir::Expr& e, Scope& scope);
  UniformPlan uniformPlanOfType(const ValueType& t, Scope& scope);
  UniformPlan uniformPlan(const ir::Sampler& s, ir::VarId v, Scope& scope);
  CompiledLearnRule compileLearnRule(const ir::Generator& g, const ir::LearnRule& r);

  Program& program_;
  const ir::Span* span_ = nullptr;
  int inlineDepth_ = 0;
};

}  // namespace cbtl::rt
