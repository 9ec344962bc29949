// Factor.h — one learned factor of a generator's model for one key: an interval, a threshold or a table.
//
// A generator's model is the product of its factors: P(holds) = prod_k P_k(holds | feature_k).
#pragma once

#include "IntervalModel.h"
#include "TableModel.h"
#include "ThresholdModel.h"

#include "ir/ConstraintGraph.h"

#include <string>
#include <variant>

namespace cbtl::model {

class Factor {
 public:
  // A fresh (prior) factor as the generator declares it.
  static Factor fromSpec(const ir::ModelFactor& spec);

  const std::string& label() const { return label_; }
  bool isTable() const { return std::holds_alternative<TableModel>(model_); }

  double probability(double feature) const;          // interval / threshold
  double probability(const std::string& key) const;  // table
  void observe(double feature, bool holds);
  void observe(const std::string& key, bool holds);
  void reset();

  const std::variant<IntervalModel, ThresholdModel, TableModel>& model() const { return model_; }
  std::variant<IntervalModel, ThresholdModel, TableModel>& model() { return model_; }

 private:
  Factor(std::string label, std::variant<IntervalModel, ThresholdModel, TableModel> m)
      : label_(std::move(label)), model_(std::move(m)) {}
  std::string label_;
  std::variant<IntervalModel, ThresholdModel, TableModel> model_;
};

}  // namespace cbtl::model
