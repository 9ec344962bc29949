// GeneratorChecker.h — the `check-generators` pass: personalized constraint generators are well formed.
//
// Checks, for every `personal` declaration: at least one parameter (the arity) of a variable type; at
// most one `when` clause whose patterns name distinct parameters and are valid globs or regexes; exactly
// one `model` clause whose factors are known kinds with valid arguments and real-valued features; `per`
// keys that are captures, discrete parameters or discrete expressions over the parameters and observations
// (never over decision variables); constant probabilities for `accept` and `fallback`; and
// learning rules whose events exist, whose binder count and types fit the event, whose labels are bool
// and name factors when the model is a product, and which bind every parameter a labelled factor or a key reads.
// Reports E04xx and W0402. (W0401, a pattern that matches no variable, needs the instantiated variable
// names and is reported by lowering.)
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"

#include <memory>
#include <vector>

namespace cbtl {

bool checkGenerators(const std::vector<std::unique_ptr<Module>>& modules, DiagnosticEngine& diags);

// The model kinds the compiler knows, in the order `cbtlc explain E0404` lists them.
const std::vector<std::string>& modelKinds();

// A factor's name: its label, or its kind (numbered when several unlabelled factors share a kind).
std::string generatorFactorName(const PersonalDecl& g, const ModelFactor& f);

// What a `per` key is. A bare name is a parameter if one has that name, else a capture of the patterns; anything
// else is an expression (a bare observation or constant included). Invalid: a bare name that is none of these.
// Meaningful after the generator checker has collected the captures.
enum class PerKeyKind { Param, Capture, Expression, Invalid };
PerKeyKind perKeyKind(const PersonalDecl& g, const PerKey& key);

// Generator parameters that an expression reads (by parameter index, sorted, unique).
std::vector<int> paramsRead(const Expr* e);

}  // namespace cbtl
