#include "runtime/model/Factor.h"

#include "ir/OpNames.h"

#include <fmt/format.h>

#include <stdexcept>

namespace cbtl::model {

Factor Factor::fromSpec(const ir::ModelFactor& spec, double fallback,
                        const std::shared_ptr<const textpref::TextBackend>& textBackend) {
  switch (spec.kind) {
    case ir::FactorKind::Interval:
      return Factor(spec.label, IntervalModel(spec.lo, spec.hi));
    case ir::FactorKind::Threshold: {
      const auto dir = spec.direction == ir::ThresholdDirection::Below ? ThresholdModel::Direction::Below
                                                                       : ThresholdModel::Direction::Above;
      return Factor(spec.label, ThresholdModel(spec.lo, spec.hi, dir));
    }
    case ir::FactorKind::Table:
      return Factor(spec.label, TableModel{});
    case ir::FactorKind::Text:
      return Factor(spec.label, TextFactor(spec, fallback, textBackend));
  }
  throw std::invalid_argument(
      fmt::format("model kind {} of factor '{}' is not supported", static_cast<int>(spec.kind), spec.label));
}

double Factor::probability(double feature) const {
  if (const auto* i = std::get_if<IntervalModel>(&model_)) return i->probability(feature);
  if (const auto* t = std::get_if<ThresholdModel>(&model_)) return t->probability(feature);
  return 0.5;
}

double Factor::posterior(double feature) const {
  if (const auto* i = std::get_if<IntervalModel>(&model_)) return i->posterior(feature);
  return probability(feature);
}

double Factor::probability(const std::string& key) const {
  if (const auto* t = std::get_if<TableModel>(&model_)) return t->probability(key);
  return 0.5;
}

double Factor::probability(const textpref::Item& subject, std::span<const textpref::Item> available,
                           const KeyedContext& context) const {
  if (const auto* t = std::get_if<TextFactor>(&model_)) return t->probability(subject, available, context);
  return 0.5;
}

void Factor::observe(double feature, bool holds) {
  if (auto* i = std::get_if<IntervalModel>(&model_))
    i->observe(feature, holds);
  else if (auto* t = std::get_if<ThresholdModel>(&model_))
    t->observe(feature, holds);
}

void Factor::observeAll(std::span<const std::pair<double, bool>> points) {
  if (auto* i = std::get_if<IntervalModel>(&model_))
    i->observeAll(points);
  else if (auto* t = std::get_if<ThresholdModel>(&model_)) {
    for (const auto& [x, holds] : points) t->observe(x, holds);  // already constant time per point
  }
}

void Factor::observe(const std::string& key, bool holds) {
  if (auto* t = std::get_if<TableModel>(&model_)) t->observe(key, holds);
}

textpref::Status Factor::observe(const textpref::Item& subject, bool holds, const textpref::Context& context) {
  if (auto* t = std::get_if<TextFactor>(&model_)) return t->learn(subject, holds, context);
  return {};
}

void Factor::reset() {
  std::visit([](auto& m) { m.reset(); }, model_);
}

std::size_t Factor::evidenceCount() const {
  if (const auto* i = std::get_if<IntervalModel>(&model_)) return i->data().size();
  if (const auto* t = std::get_if<ThresholdModel>(&model_)) return t->data().size();
  if (const auto* tb = std::get_if<TableModel>(&model_)) return tb->entries().size();
  if (const auto* tx = std::get_if<TextFactor>(&model_)) return tx->historySize();
  return 0;
}

}  // namespace cbtl::model
