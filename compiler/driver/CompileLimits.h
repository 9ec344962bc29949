// CompileLimits.h — every resource limit of the compiler, in one table.
//
// The compiler promises that no input, mistyped or hostile, makes it (or the runtime that executes what it
// accepts) run for long or exhaust memory: a program `cbtlc check` accepts can run. Everything that grows
// faster than the source text (families, unrolled quantifiers, inlined functions, generator instances,
// quantifier nests) is measured before the expensive work and refused with a located diagnostic when it
// exceeds its limit here. Each limit is generous: every domain program and every golden program stays orders
// of magnitude below it (docs/compiler.md, *Limits*, gives the figures and why each limit is where it is).
//
// The limits are constants, not options: a program that compiles on one machine compiles on every other.
#pragma once

#include <cstddef>

namespace cbtl {

struct CompileLimits {
  // --- parse, build-ast (E0108) ---
  // Brackets and prefix operators nest at most this deep (the parser's token pre-scan), so that the
  // recursive-descent parser and every recursive pass stay far from the stack's end.
  static constexpr int kMaxNesting = 200;
  // An expression tree has at most this many levels (long operator chains such as a+a+...+a).
  static constexpr int kMaxExprDepth = 1000;

  // --- lower (E0317) ---
  // One integer range used as a family index or a `sample ... for` set has at most this many members.
  static constexpr std::size_t kMaxSetSize = 100000;
  // The whole graph, in units of one variable, constraint, sampler, cost or action plus one per expression
  // node, every call of a user function counted with its inlined body (the runtime inlines it).
  static constexpr std::size_t kMaxGraphSize = 2000000;
  // A top-level forall is unrolled only while the number of instances stays at most this; beyond it the
  // constraint keeps its quantifier (same meaning, one hyperedge). Not an error.
  static constexpr std::size_t kMaxUnrolled = 10000;

  // --- check-types: inlining of user functions (E0319) ---
  // The runtime inlines every call of a user function (runtime/core/ProgramCompiler.cpp, compileCall), so a
  // function that calls another twice doubles its size at each level: 60 lines can expand into 2^60 nodes.
  // A function's body, with every call it makes inlined, has at most this many expression nodes.
  static constexpr std::size_t kMaxInlinedNodes = 100000;
  // ... and at most this many levels (the expression depth limit above, which the runtime's recursive
  // compiler and evaluator are known to cope with, applies to what they see after inlining).
  static constexpr std::size_t kMaxInlinedDepth = 1000;
  // A call inlines at most this many nested calls (the function itself, the calls in its body, and so on):
  // the runtime refuses a deeper expansion ("expands too deeply", its limit is 64), so the compiler must not
  // accept one.
  static constexpr std::size_t kMaxCallDepth = 64;

  // --- lower: quantifiers (E0320) ---
  // A constraint, cost or guard is evaluated by the runtime every time a candidate is checked; a nest of
  // quantifiers costs the product of the sizes of the sets it ranges over per evaluation. That product (over
  // the sets known at compile time: enums, item sets, constant ranges and lists) is at most this.
  static constexpr std::size_t kMaxQuantifierBindings = 1000000;

  // --- lower: personalized generators (E0418) ---
  // The runtime creates one instance per tuple of distinct variables that a generator's patterns match, in
  // every task, each with its own compiled guard and features. All generators together make at most this
  // many instances ...
  static constexpr std::size_t kMaxGeneratorInstances = 100000;
  // ... and finding them takes at most this many steps: the runtime looks at every variable of a task for
  // each parameter's type, then tries every candidate for each parameter given the ones before it, testing its
  // patterns; each variable looked at, candidate tried and pattern tested is one step.
  static constexpr std::size_t kMaxGeneratorMatchSteps = 2000000;
};

}  // namespace cbtl
