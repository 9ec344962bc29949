#include "runtime/solver/PersonalExplanation.h"

#include "runtime/core/TextContext.h"
#include "runtime/model/Entropy.h"
#include "runtime/solver/PersonalEvaluator.h"
#include "runtime/solver/StagedPlan.h"

#include <algorithm>

namespace cbtl::solver {

std::vector<InstanceExplanation> explainPersonal(const Csp& csp, const std::vector<double>& assignment) {
  std::vector<InstanceExplanation> out;
  if (csp.program == nullptr || csp.instances == nullptr || csp.user == nullptr) return out;
  const rt::Program& program = *csp.program;
  std::vector<double> values = assignment, observation = csp.observation;
  values.resize(std::max<std::size_t>(program.assignmentWidth(), 1), 0.0);
  observation.resize(std::max<std::size_t>(program.observationWidth(), 1), 0.0);
  std::vector<double> frame(program.frameSize() + 1, 0.0);
  const rt::EvalContext ctx{values.data(), observation.data(), frame.data(), program.callContext()};
  PersonalEvaluator evaluator(program, *csp.instances, *csp.user);
  if (csp.plan != nullptr) csp.plan->changed();
  for (std::uint32_t i = 0; i < csp.instances->size(); ++i) {
    const rt::PersonalInstance& inst = (*csp.instances)[i];
    const ir::Generator& g = program.graph().generators.at(inst.generator);
    InstanceExplanation e;
    e.name = inst.name;
    e.key = evaluator.key(i, ctx);
    e.accept = g.accept;
    e.inCsp = std::any_of(csp.constraints.begin(), csp.constraints.end(),
                          [&](const ConstraintRef& c) { return c.personal() && c.index == i; });
    // Judged in the state its skill starts in, as the solver and the re-check judge it.
    const std::uint32_t stage = i < csp.instanceStage.size() ? csp.instanceStage[i] : 0;
    if (csp.plan != nullptr && stage != kAnyStage) e.reached = csp.plan->enterStage(stage, ctx);
    const PersonalValue v = evaluator.evaluate(i, ctx);
    e.applies = v.applies;
    e.probability = v.probability;
    e.holds = evaluator.holds(i, v);
    e.entropyBits = model::bernoulliEntropyBits(v.posterior);
    const auto& factors = csp.user->generator(inst.generator).factors(e.key);
    for (const auto& f : factors) e.evidence += f.evidenceCount();
    for (std::size_t k = 0; k < factors.size() && k < inst.features.size(); ++k) {
      const auto* text = std::get_if<model::TextFactor>(&factors[k].model());
      if (text == nullptr) continue;
      TextFactorExplanation t;
      t.factor = factors[k].label();
      if (inst.features[k] != UINT32_MAX) {
        double raw[rt::kMaxValueWidth];
        program.pool().eval(inst.features[k], ctx, raw);
        t.subject = program.render(inst.featureTypes[k], raw);
      }
      if (k < inst.contexts.size() && !inst.contexts[k].empty()) {
        std::vector<double> contextValues;
        rt::evaluateContext(program, inst.contexts[k], ctx, contextValues);
        t.context = textpref::describeContext(rt::renderContext(program, inst.contexts[k], contextValues));
      }
      t.theta = text->model().thetaText();
      e.text.push_back(std::move(t));
    }
    out.push_back(std::move(e));
  }
  if (csp.plan != nullptr) csp.plan->enterStage(0, ctx);  // back to the start state, as the re-check leaves it
  return out;
}

}  // namespace cbtl::solver
