// Factor.h — one learned factor of a generator's model for one key: an interval, a threshold, a table or a text
// (text-preference) model.
//
// A generator's model is the product of its factors: P(holds) = prod_k P_k(holds | feature_k). Interval and
// threshold factors read a real feature, tables the rendered value of their key, and text factors the subject as
// a textpref::Item (ItemDescriptors.h).
#pragma once

#include "runtime/model/IntervalModel.h"
#include "runtime/model/TableModel.h"
#include "runtime/model/TextFactor.h"
#include "runtime/model/ThresholdModel.h"

#include "ir/ConstraintGraph.h"

#include <memory>
#include <span>
#include <string>
#include <variant>

namespace cbtl::model {

class Factor {
 public:
  using Model = std::variant<IntervalModel, ThresholdModel, TableModel, TextFactor>;

  // A fresh (prior) factor as the generator declares it. A text factor gets its model from `textBackend`
  // (null: the offline default) and falls back to the generator's `fallback`. Throws std::invalid_argument for a
  // `kind` that is no FactorKind enumerator.
  static Factor fromSpec(const ir::ModelFactor& spec, double fallback = 0.5,
                         const std::shared_ptr<const textpref::TextBackend>& textBackend = nullptr);

  const std::string& label() const { return label_; }
  bool isTable() const { return std::holds_alternative<TableModel>(model_); }
  bool isText() const { return std::holds_alternative<TextFactor>(model_); }

  double probability(double feature) const;  // interval / threshold
  // interval: the full posterior predictive for the entropy of exploration (IntervalModel::posterior);
  // threshold: probability()
  double posterior(double feature) const;
  double probability(const std::string& key) const;  // table
  // text: see TextFactor::probability (`available` is the subject's domain for relative scaling)
  double probability(const textpref::Item& subject, std::span<const textpref::Item> available,
                     const KeyedContext& context = KeyedContext::none()) const;
  void observe(double feature, bool holds);
  // interval / threshold: observes every (feature, holds) in order, the same as one observe() each but linear.
  void observeAll(std::span<const std::pair<double, bool>> points);
  void observe(const std::string& key, bool holds);
  // text: learns one (subject, context, liked) record; the status says whether theta could be updated
  textpref::Status observe(const textpref::Item& subject, bool holds,
                           const textpref::Context& context = textpref::Context{});
  void reset();
  // The labelled examples the factor holds (interval and threshold points, table entries, text records): 0 means
  // what it says is its prior, not anything learned.
  std::size_t evidenceCount() const;

  const Model& model() const { return model_; }
  Model& model() { return model_; }

 private:
  Factor(std::string label, Model m) : label_(std::move(label)), model_(std::move(m)) {}
  std::string label_;
  Model model_;
};

}  // namespace cbtl::model
