// ThresholdModel.h — the one-sided threshold model: the constraint holds iff x >= theta ("above") or
// x <= theta ("below"), theta ~ U[lo, hi].
//
// Each labelled example shrinks theta's interval; the posterior is uniform on what survives, so the
// predictive is 0 / linear / 1 across it. An emptied or degenerate interval (contradictory labels) gives
// 0.5 everywhere: the model admits it does not know.
#pragma once

#include <utility>
#include <vector>

namespace cbtl::model {

class ThresholdModel {
 public:
  enum class Direction { Above, Below };
  ThresholdModel(double lo, double hi, Direction direction);

  void observe(double x, bool holds);
  void reset();
  double probability(double x) const;

  double lo() const { return lo_; }
  double hi() const { return hi_; }
  double posteriorLo() const { return curLo_; }
  double posteriorHi() const { return curHi_; }
  Direction direction() const { return direction_; }
  const std::vector<std::pair<double, bool>>& data() const { return data_; }

 private:
  double lo_, hi_, curLo_, curHi_;
  Direction direction_;
  std::vector<std::pair<double, bool>> data_;
};

}  // namespace cbtl::model
