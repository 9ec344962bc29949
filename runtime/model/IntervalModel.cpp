#include "runtime/model/IntervalModel.h"

#include <algorithm>
#include <limits>

namespace cbtl::model {

IntervalModel::IntervalModel(double lo, double hi) : lo_(std::min(lo, hi)), hi_(std::max(lo, hi)) { refit(); }

void IntervalModel::observe(double x, bool holds) {
  data_.emplace_back(x, holds);
  refit();
}

void IntervalModel::observeAll(std::span<const std::pair<double, bool>> points) {
  data_.insert(data_.end(), points.begin(), points.end());
  refit();  // the fit depends on the data only, not on the order it arrived in
}

void IntervalModel::reset() {
  data_.clear();
  refit();
}

void IntervalModel::refit() {
  double minP = std::numeric_limits<double>::infinity(), maxP = -minP;
  for (const auto& [x, y] : data_) {
    if (y) {
      minP = std::min(minP, x);
      maxP = std::max(maxP, x);
    }
  }
  hasPositive_ = minP <= maxP;
  gapEnds_.clear();
  gapMass_ = 0;
  if (!hasPositive_) {
    x1_ = x2_ = lo_;
    x3_ = x4_ = hi_;
    gapEnds_.push_back(lo_);
    for (const auto& [x, y] : data_) {
      if (lo_ < x && x < hi_) gapEnds_.push_back(x);
    }
    gapEnds_.push_back(hi_);
    std::sort(gapEnds_.begin() + 1, gapEnds_.end() - 1);
    for (std::size_t g = 0; g + 1 < gapEnds_.size(); ++g) {
      const double w = gapEnds_[g + 1] - gapEnds_[g];
      gapMass_ += w * w / 2;
    }
    return;
  }
  x2_ = std::clamp(minP, lo_, hi_);
  x3_ = std::clamp(maxP, lo_, hi_);
  x1_ = lo_;
  x4_ = hi_;
  for (const auto& [x, y] : data_) {
    if (y) continue;
    if (x < x2_)
      x1_ = std::max(x1_, x);
    else if (x > x3_)
      x4_ = std::min(x4_, x);
  }
}

double IntervalModel::probability(double x) const {
  if (!hasPositive_ && nearRefusal(x)) return 0;
  double pa;  // P(a <= x), a ~ U[x1, x2]
  if (x >= x2_)
    pa = 1;
  else if (x < x1_)
    pa = 0;
  else
    pa = (x - x1_) / (x2_ - x1_);
  double pb;  // P(b >= x), b ~ U[x3, x4]
  if (x <= x3_)
    pb = 1;
  else if (x > x4_)
    pb = 0;
  else
    pb = (x4_ - x) / (x4_ - x3_);
  return std::clamp(pa * pb, 0.0, 1.0);
}

bool IntervalModel::nearRefusal(double x) const {
  if (gapEnds_.size() <= 2) return false;  // no negative inside the bounds
  const double radius = kRefusalRadius * (hi_ - lo_);
  // gapEnds_ is lo, the negatives inside (lo, hi) in ascending order, hi: the nearest negative is next to x.
  const auto negativesBegin = gapEnds_.begin() + 1, negativesEnd = gapEnds_.end() - 1;
  const auto above = std::lower_bound(negativesBegin, negativesEnd, x);
  if (above != negativesEnd && *above - x < radius) return true;
  return above != negativesBegin && x - *(above - 1) < radius;
}

double IntervalModel::posterior(double x) const {
  if (hasPositive_ || !(gapMass_ > 0)) return probability(x);
  if (!(lo_ < x && x < hi_)) return 0;
  // The gap holding x: the first end above it, and the one before.
  const auto above = std::upper_bound(gapEnds_.begin(), gapEnds_.end(), x);
  if (above == gapEnds_.begin() || above == gapEnds_.end()) return 0;
  const double u = *(above - 1), v = *above;
  return std::clamp((x - u) * (v - x) / gapMass_, 0.0, 1.0);
}

}  // namespace cbtl::model
