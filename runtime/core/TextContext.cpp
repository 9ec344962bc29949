#include "runtime/core/TextContext.h"

#include <cmath>

namespace cbtl::rt {

CompiledContext compileContext(ProgramCompiler& compiler, const Program& program, const ir::ModelFactor& factor,
                               ProgramCompiler::Scope& scope) {
  CompiledContext out;
  for (const auto& entry : factor.context) {
    out.names.push_back(entry.name);
    out.nodes.push_back(compiler.compile(entry.value, scope));
    out.types.push_back(program.typeOf(entry.value.type));
  }
  return out;
}

bool evaluateContext(const Program& program, const CompiledContext& context, const EvalContext& ctx,
                     std::vector<double>& values) {
  bool changed = values.size() != context.nodes.size();
  values.resize(context.nodes.size(), std::nan(""));
  for (std::size_t i = 0; i < context.nodes.size(); ++i) {
    const double v = program.pool().evalScalar(context.nodes[i], ctx);
    if (!(values[i] == v)) {
      values[i] = v;
      changed = true;
    }
  }
  return changed;
}

textpref::Context renderContext(const Program& program, const CompiledContext& context,
                                const std::vector<double>& values) {
  textpref::Context out;
  for (std::size_t i = 0; i < context.nodes.size() && i < values.size(); ++i) {
    out.fields[context.names[i]] = {program.render(context.types[i], &values[i])};
    // An item carries what its declaration says about it, so that what is learned in one context (ketchup with
    // french fries) can reach another that shares a descriptor (tater tots, also fried potato).
    if (const textpref::Item* item = program.itemDescriptors().item(context.types[i], values[i]))
      for (const auto& [field, strings] : item->descriptors) out.fields[context.names[i] + "." + field] = strings;
  }
  return out;
}

}  // namespace cbtl::rt
