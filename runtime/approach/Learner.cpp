#include "runtime/approach/Learner.h"

#include "runtime/approach/ValueBridge.h"
#include "runtime/core/TextContext.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace cbtl::approach {

Learner::Learner(const rt::Program& program) : program_(program) {
  for (const auto& g : program_.generators()) {
    std::vector<std::vector<std::size_t>> perRule;
    for (const auto& r : g.rules) {
      std::vector<std::size_t> binders;
      for (const auto& key : g.source->perKeys) {
        if (key.expr) {  // evaluated from the rule's compiled key (CompiledLearnRule::keys)
          binders.push_back(SIZE_MAX);
          continue;
        }
        std::size_t found = SIZE_MAX;
        for (std::size_t i = 0; i < r.source->binds.size(); ++i) {
          if (r.source->binds[i] == key.name) found = i;
        }
        if (found == SIZE_MAX) {
          throw rt::RuntimeError(rt::Program::where(r.source->span),
                                 fmt::format("learning rule '{}' does not bind '{}', a 'per' key of '{}'",
                                             r.source->event, key.name, g.source->name));
        }
        binders.push_back(found);
      }
      perRule.push_back(std::move(binders));
    }
    keyBinders_.push_back(std::move(perRule));
  }
}

LearnReport Learner::learn(const std::vector<sim::FeedbackEvent>& events, model::UserModel& user,
                           const StepWorld& world) const {
  LearnReport report;
  const auto& pool = program_.pool();
  std::vector<double> assignment = world.assignment, observation = world.observation;
  assignment.resize(std::max<std::size_t>(program_.assignmentWidth(), 1), 0.0);
  observation.resize(std::max<std::size_t>(program_.observationWidth(), 1), 0.0);
  std::vector<double> frame;
  for (const auto& ev : events) {
    // An event the program does not declare is a simulator that does not fit the program: said, never dropped.
    const auto& declared = program_.graph().feedback;
    if (std::none_of(declared.begin(), declared.end(), [&](const ir::Function& f) { return f.name == ev.name; })) {
      report.problems.push_back(
          fmt::format("event '{}' is not declared by the program (no `feedback {}(...)`)", ev.name, ev.name));
      continue;
    }
    for (std::size_t gi = 0; gi < program_.generators().size(); ++gi) {
      const auto& g = program_.generators()[gi];
      for (std::size_t ri = 0; ri < g.rules.size(); ++ri) {
        const auto& r = g.rules[ri];
        if (r.source->event != ev.name) continue;
        if (ev.args.size() != r.binderTypes.size()) {
          report.problems.push_back(fmt::format("event '{}' has {} arguments, its declaration {}", ev.name,
                                                ev.args.size(), r.binderTypes.size()));
          continue;
        }
        frame.assign(std::max<std::size_t>(r.frameWidth, program_.frameSize()) + 1, 0.0);
        bool ok = true;
        for (std::size_t i = 0; i < ev.args.size() && ok; ++i) {
          std::string error;
          if (!fromSimValue(program_, r.binderTypes[i], ev.args[i], frame.data() + r.binderFrame[i], error)) {
            report.problems.push_back(fmt::format("event '{}' argument {}: {}", ev.name, i + 1, error));
            ok = false;
          }
        }
        if (!ok) continue;
        rt::EvalContext ctx{assignment.data(), observation.data(), frame.data(), program_.callContext()};
        if (r.condition && !pool.evalBool(*r.condition, ctx)) continue;
        std::string key;
        const auto& binders = keyBinders_[gi][ri];
        double keyValue[rt::kMaxValueWidth];
        for (std::size_t k = 0; k < binders.size(); ++k) {
          key += k ? "|" : "";
          if (const std::size_t b = binders[k]; b != SIZE_MAX) {
            key += program_.render(r.binderTypes[b], frame.data() + r.binderFrame[b]);
          } else {
            pool.eval(r.keys[k], ctx, keyValue);
            key += program_.render(r.keyTypes[k], keyValue);
          }
        }
        auto& factors = user.generator(gi).mutableFactors(key);
        for (std::size_t l = 0; l < r.labels.size(); ++l) {
          const auto [factor, labelNode] = r.labels[l];
          const bool holds = pool.evalBool(labelNode, ctx);
          auto& f = factors[static_cast<std::size_t>(factor)];
          const std::uint32_t feature = r.features[l];
          if (f.isTable()) {
            if (feature == UINT32_MAX) continue;
            double v[rt::kMaxValueWidth];
            pool.eval(feature, ctx, v);
            const auto& spec = *g.factors[static_cast<std::size_t>(factor)].source;
            f.observe(program_.render(program_.typeOf(spec.feature->type), v), holds);
          } else if (f.isText()) {
            if (feature == UINT32_MAX) continue;
            const auto& spec = *g.factors[static_cast<std::size_t>(factor)].source;
            const rt::ValueType type = program_.typeOf(spec.feature->type);
            const double value = pool.evalScalar(feature, ctx);
            std::optional<textpref::Item> subject;
            if (const textpref::Item* item = program_.itemDescriptors().item(type, value)) {
              subject = *item;
            } else if (type.kind == rt::ValueKind::Text) {
              subject = textpref::Item{program_.render(type, &value), {}};
            }
            if (!subject) {
              report.problems.push_back(
                  fmt::format("event '{}': the subject of '{}' ({} value {}) is not a value of its type", ev.name,
                              g.source->name, type.typeName, value));
              continue;
            }
            textpref::Context context;
            if (const auto& compiled = r.contexts[l]; !compiled.empty()) {
              std::vector<double> values;
              rt::evaluateContext(program_, compiled, ctx, values);
              context = rt::renderContext(program_, compiled, values);
            }
            if (const textpref::Status s = f.observe(*subject, holds, context); !s.ok()) {
              report.modelErrors.push_back(fmt::format("{}: learning from '{}' about '{}': {}", g.source->name, ev.name,
                                                       subject->name, s.error().describe()));
            }
          } else {
            if (feature == UINT32_MAX) continue;
            f.observe(pool.evalScalar(feature, ctx), holds);
          }
          ++report.labels;
        }
      }
    }
  }
  return report;
}

}  // namespace cbtl::approach
