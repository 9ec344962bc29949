#include "runtime/core/Program.h"

#include "runtime/core/ProgramCompiler.h"

#include <algorithm>

namespace cbtl::rt {

Program::Program(const ir::ConstraintGraph& graph, Builtins builtins) : graph_(graph), builtins_(std::move(builtins)) {
  callContext_ = CallContext{&strings_, builtins_.host().get()};
  strings_.intern("");  // text id 0 is the empty string: the value of an uninitialized text variable
  for (const auto& c : graph_.constants) constants_[c.name] = &c;
  for (const auto& f : graph_.functions) functions_[f.name] = &f;
  layoutVariables();
  layoutObservations();
  // The order fixes where each declaration's nodes sit in the pool.
  ProgramCompiler compiler(*this);
  inits_ = compiler.compileInitialValues();
  constraints_ = compiler.compileConstraints();
  domainChecks_ = compiler.compileDomainChecks();
  samplers_ = compiler.compileSamplers();
  for (const auto& s : samplers_) {
    maxSamplerOut_ = std::max(maxSamplerOut_, s.outWidth);
    maxSamplerArgs_ = std::max(maxSamplerArgs_, s.argsWidth);
  }
  generators_ = compiler.compileGenerators();
  itemDescriptors_ = ItemDescriptors(graph_, [&compiler](const ir::Expr& e) { return compiler.constantStrings(e); });
  costs_ = compiler.compileCosts();
}

const ir::Constant* Program::findConstant(const std::string& name) const {
  auto it = constants_.find(name);
  return it == constants_.end() ? nullptr : it->second;
}

const ir::Function* Program::findFunction(const std::string& name) const {
  auto it = functions_.find(name);
  return it == functions_.end() ? nullptr : it->second;
}

const ir::Observation* Program::findObservation(const std::string& name) const {
  for (const auto& o : graph_.observations) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

bool Program::samplerReadsWorld(std::uint32_t sampler) const {
  const CompiledSampler& s = samplers_.at(sampler);
  if (s.impl != nullptr && builtins_.readsHost(s.impl)) return true;
  for (std::uint32_t a : s.args)
    if (readsWorld(a)) return true;
  for (const UniformPlan& u : s.uniform) {
    for (std::uint32_t n : u.lo)
      if (readsWorld(n)) return true;
    for (std::uint32_t n : u.hi)
      if (readsWorld(n)) return true;
  }
  return false;
}

}  // namespace cbtl::rt
