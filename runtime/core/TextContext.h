// TextContext.h — compiling and evaluating a text model's context (`model text(subject, context: [foodOnPlate,
// mealSetting])`), compiled against one scope (CompiledContext, Program.h), and its value as the text-preference models
// see it.
//
// Each entry is an observation or a generator parameter of a discrete scalar type (the compiler checks it), so a
// value is one double: a text's string id, an enum member's or item entry's index, a bool or an int. A
// personalized instance compiles its factors' contexts over its own variables (the value the CSP reads); a
// learning rule over its frame and the observation of the step its feedback is about, so that every learned
// record carries the situation in which the user reacted.
#pragma once

#include "runtime/core/ProgramCompiler.h"
#include "runtime/textpref/Item.h"

#include "ir/ConstraintGraph.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::rt {

// Compiles `factor`'s context in `scope`. Throws RuntimeError (located by the compiler) when an entry cannot be
// compiled there.
CompiledContext compileContext(ProgramCompiler& compiler, const Program& program, const ir::ModelFactor& factor,
                               ProgramCompiler::Scope& scope);

// Evaluates every entry into `values` (resized to one double per entry); true when any value differs from what
// `values` held, so a caller can keep the rendered context until it changes.
bool evaluateContext(const Program& program, const CompiledContext& context, const EvalContext& ctx,
                     std::vector<double>& values);

// The context as the models see it: {name: [rendered value]} per entry, and for an item entry one more field per
// declared descriptor, {name.field: [its strings]} (ItemDescriptors.h), e.g. {"foodOnPlate": ["tots"],
// "foodOnPlate.kind": ["fried", "potato"]}.
textpref::Context renderContext(const Program& program, const CompiledContext& context,
                                const std::vector<double>& values);

}  // namespace cbtl::rt
