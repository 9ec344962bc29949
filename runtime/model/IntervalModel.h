// IntervalModel.h — the bounded 1-D interval model: the constraint holds iff a <= x <= b, with the public
// outer bounds lo <= a <= b <= hi and independent uniform priors on a and b.
//
// With positives P and negatives N the version space is a product of two intervals, so the posterior
// predictive is exact: P(holds | x) = P(a <= x) * P(b >= x) with a ~ U[x1, x2], b ~ U[x3, x4], where
// x2 = min P, x3 = max P, x1 = the largest negative below x2 (else lo), x4 = the smallest negative above x3
// (else hi) — a trapezoid. Before the first positive the model predicts 1 on [lo, hi] and 0 outside (as the
// reference does: the constraint is optimistic until something is liked), except within kRefusalRadius of the
// bounds' width (1 %) of a negative, where it predicts 0: a value the user just refused is not offered again
// while nothing is known to be liked. The radius is what separates "the same value again" from a new one: a
// robot's executed handover point differs from the one the solver chose by its IK tolerance, so an exact match
// never recurs, and without it Books' solver handed one refused spot over four times in a row (seed 7).
//
// posterior() is the full posterior predictive under a uniform prior over the intervals lo <= a <= b <= hi,
// which the paper uses for the entropy of active learning (its appendix: maximum-likelihood values for the
// constraint, the full posterior for entropy). Once a positive is known it equals probability() (the
// trapezoid is that posterior). Before, it is what the optimistic constraint hides: with negatives
// n_1 < ... < n_k splitting [lo, hi] into gaps [u, v], the interval lies inside one gap, so
// P(x) = (x - u)(v - x) / sum over gaps of (v - u)^2 / 2 for x in gap [u, v]: 0 at every negative, at most
// 1/2 (the middle of [lo, hi] with no data). Without it CBTL has no uncertainty to follow before its first
// positive (Cooking's first meals were random). A generator declared `explore accepted` takes its entropy from
// probability() instead (solver/PersonalEvaluator.h): Books' range of motion, whose bounds are loose around
// the user's, so that the middle of a gap is far out of reach.
//
// Differences from the reference, on purpose: the hypothesis is closed (x = hi is inside the known range,
// the reference's half-open test made the top of the range impossible); negatives lying between positives
// contradict them (noisy or shifted preferences) and are left out of the fit instead of pushing x1 above x2,
// so probabilities always stay within [0, 1].
#pragma once

#include <span>
#include <utility>
#include <vector>

namespace cbtl::model {

class IntervalModel {
 public:
  static constexpr double kRefusalRadius = 0.01;  // fraction of hi - lo (see above)

  IntervalModel(double lo, double hi);

  void observe(double x, bool holds);
  // Adds every point, then fits once: the same model as observing them one by one in order, in linear time
  // (observe() refits over all data each time).
  void observeAll(std::span<const std::pair<double, bool>> points);
  void reset();
  double probability(double x) const;
  double posterior(double x) const;

  double lo() const { return lo_; }
  double hi() const { return hi_; }
  // The trapezoid's corners x1 <= x2 <= x3 <= x4 (x1 = x2 = lo, x3 = x4 = hi before any positive).
  double x1() const { return x1_; }
  double x2() const { return x2_; }
  double x3() const { return x3_; }
  double x4() const { return x4_; }
  bool hasPositive() const { return hasPositive_; }
  const std::vector<std::pair<double, bool>>& data() const { return data_; }

 private:
  void refit();
  bool nearRefusal(double x) const;  // within kRefusalRadius (hi - lo) of a negative inside the bounds

  double lo_, hi_;
  double x1_, x2_, x3_, x4_;
  bool hasPositive_ = false;
  std::vector<std::pair<double, bool>> data_;
  std::vector<double> gapEnds_;  // before the first positive: lo, the negatives inside (lo, hi) sorted, hi
  double gapMass_ = 0;           // sum over gaps of (v - u)^2 / 2
};

}  // namespace cbtl::model
