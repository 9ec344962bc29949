#include "runtime/solver/PersonalEvaluator.h"

#include "runtime/core/TextContext.h"

#include <cmath>

namespace cbtl::solver {

namespace {

// The observation offset of the membership flags of the observed set the factor's subject variable draws from
// (`var book : Book in pickable`), when the factor reads one parameter whose instance variable has such a domain.
std::optional<std::uint32_t> observedDomainFlags(const rt::Program& program, const rt::PersonalInstance& inst,
                                                 const ir::ModelFactor& factor) {
  if (factor.params.size() != 1) return std::nullopt;
  const ir::Generator& g = program.graph().generators.at(inst.generator);
  for (std::size_t p = 0; p < g.params.size() && p < inst.vars.size(); ++p) {
    if (g.params[p].name != factor.params[0]) continue;
    const ir::Domain& domain = program.graph().variables.at(inst.vars[p]).domain;
    if (domain.set && domain.set->op == ir::Op::Obs) return program.observationOffset(domain.set->text);
  }
  return std::nullopt;
}

}  // namespace

PersonalEvaluator::PersonalEvaluator(const rt::Program& program, const std::vector<rt::PersonalInstance>& instances,
                                     const model::UserModel& user)
    : program_(program), instances_(instances), user_(user), cache_(instances.size()) {
  for (const auto& inst : instances_) {
    const ir::Generator& g = program_.graph().generators.at(inst.generator);
    acceptThreshold_.push_back(g.accept * std::exp(-1e-3));
    entropyFromAccepted_.push_back(g.exploreAccepted);
    std::size_t dynamic = 0;
    for (const auto& part : inst.key) dynamic += part.fromValue ? part.type.width : 0;
    Cache& c = cache_[acceptThreshold_.size() - 1];
    c.keyValues.assign(dynamic, std::nan(""));
    const auto& factors = program_.generators().at(inst.generator).factors;
    for (std::size_t k = 0; k < factors.size(); ++k) {
      if (factors[k].source->kind != ir::FactorKind::Text) continue;
      c.text.resize(factors.size());
      c.text[k].domain = program_.itemDescriptors().domain(inst.featureTypes[k]);
      c.text[k].flags = observedDomainFlags(program_, inst, *factors[k].source);
    }
  }
}

double PersonalEvaluator::textProbability(const rt::PersonalInstance& inst, std::size_t factor, const model::Factor& f,
                                          TextSubject& subject, double value, const rt::EvalContext& ctx) {
  const textpref::Item* item = nullptr;
  std::span<const textpref::Item> available;
  if (subject.domain != nullptr) {
    available = *subject.domain;
    if (value >= 0 && value < static_cast<double>(available.size())) item = &available[static_cast<std::size_t>(value)];
    if (subject.flags) {
      if (!subject.availableBuilt) {
        for (std::size_t i = 0; i < subject.domain->size(); ++i)
          if (ctx.observation[*subject.flags + i] != 0) subject.available.push_back((*subject.domain)[i]);
        subject.availableBuilt = true;
      }
      available = subject.available;
    }
  } else if (inst.featureTypes[factor].kind == rt::ValueKind::Text) {
    if (!(value == subject.last)) {
      const bool interned = value >= 0 && value < static_cast<double>(program_.strings().size());
      subject.owned =
          textpref::Item{interned ? program_.strings().name(static_cast<std::uint32_t>(value)) : std::string(), {}};
      subject.last = value;
    }
    item = &subject.owned;
  }
  if (item == nullptr) return program_.graph().generators.at(inst.generator).fallback;
  if (factor < inst.contexts.size() && !inst.contexts[factor].empty() &&
      rt::evaluateContext(program_, inst.contexts[factor], ctx, subject.contextValues)) {
    subject.context = model::KeyedContext(rt::renderContext(program_, inst.contexts[factor], subject.contextValues));
  }
  return f.probability(*item, available, subject.context);
}

std::string PersonalEvaluator::key(std::uint32_t instance, const rt::EvalContext& ctx) const {
  const auto& inst = instances_[instance];
  std::string key;
  double v[rt::kMaxValueWidth];
  for (std::size_t i = 0; i < inst.key.size(); ++i) {
    const auto& part = inst.key[i];
    if (i) key += "|";
    if (part.fromValue) {
      program_.pool().eval(part.node, ctx, v);
      key += program_.render(part.type, v);
    } else {
      key += part.text;
    }
  }
  return key;
}

PersonalValue PersonalEvaluator::evaluate(std::uint32_t instance, const rt::EvalContext& ctx) {
  const auto& inst = instances_[instance];
  const auto& pool = program_.pool();
  if (inst.guard && !pool.evalBool(*inst.guard, ctx)) return PersonalValue{false, 1.0, 1.0};
  const auto& state = user_.generator(inst.generator);
  Cache& c = cache_[instance];
  bool stale = c.factors == nullptr || c.version != state.version();
  double v[rt::kMaxValueWidth];
  std::size_t at = 0;
  for (const auto& part : inst.key) {
    if (!part.fromValue) continue;
    pool.eval(part.node, ctx, v);
    for (std::size_t i = 0; i < part.type.width; ++i, ++at) {
      if (c.keyValues[at] != v[i]) {
        c.keyValues[at] = v[i];
        stale = true;
      }
    }
  }
  if (stale) {
    c.factors = &state.factors(key(instance, ctx));
    c.version = state.version();
  }
  double p = 1.0, posterior = 1.0;
  const auto& factors = *c.factors;
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const std::uint32_t feature = inst.features[k];
    if (factors[k].isTable()) {
      if (feature == UINT32_MAX) continue;
      pool.eval(feature, ctx, v);
      const double pk = factors[k].probability(program_.render(inst.featureTypes[k], v));
      p *= pk;
      posterior *= pk;
    } else if (factors[k].isText()) {
      if (feature == UINT32_MAX || k >= c.text.size()) continue;
      const double pk = textProbability(inst, k, factors[k], c.text[k], pool.evalScalar(feature, ctx), ctx);
      p *= pk;
      posterior *= pk;
    } else if (feature != UINT32_MAX) {
      const double x = pool.evalScalar(feature, ctx);
      const double pk = factors[k].probability(x);
      p *= pk;
      posterior *= entropyFromAccepted_[instance] ? pk : factors[k].posterior(x);
    }
  }
  return PersonalValue{true, p, posterior};
}

bool PersonalEvaluator::holds(std::uint32_t instance, const PersonalValue& v) const {
  return !v.applies || v.probability >= acceptThreshold_[instance];
}

}  // namespace cbtl::solver
