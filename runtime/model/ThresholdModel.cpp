#include "runtime/model/ThresholdModel.h"

#include <algorithm>

namespace cbtl::model {

ThresholdModel::ThresholdModel(double lo, double hi, Direction direction)
    : lo_(std::min(lo, hi)), hi_(std::max(lo, hi)), curLo_(lo_), curHi_(hi_), direction_(direction) {}

void ThresholdModel::observe(double x, bool holds) {
  data_.emplace_back(x, holds);
  const bool above = direction_ == Direction::Above;
  // Above: holds => theta <= x; fails => theta > x. Below: holds => theta >= x; fails => theta < x.
  if (holds == above)
    curHi_ = std::min(curHi_, x);
  else
    curLo_ = std::max(curLo_, x);
}

void ThresholdModel::reset() {
  data_.clear();
  curLo_ = lo_;
  curHi_ = hi_;
}

double ThresholdModel::probability(double x) const {
  if (!(curLo_ < curHi_)) return 0.5;
  double pBelow;  // P(theta <= x)
  if (x <= curLo_)
    pBelow = 0;
  else if (x >= curHi_)
    pBelow = 1;
  else
    pBelow = (x - curLo_) / (curHi_ - curLo_);
  return direction_ == Direction::Above ? pBelow : 1.0 - pBelow;
}

}  // namespace cbtl::model
