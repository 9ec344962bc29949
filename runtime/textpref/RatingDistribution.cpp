#include "runtime/textpref/RatingDistribution.h"

#include <algorithm>
#include <cmath>

namespace cbtl::textpref {

double RatingDistribution::expectedProbability() const {
  double sum = 0.0;
  for (int r = 0; r < kRatingCount; ++r) sum += (r / 10.0) * p[static_cast<std::size_t>(r)];
  return std::clamp(sum, 0.0, 1.0);
}

double RatingDistribution::total() const {
  double sum = 0.0;
  for (double v : p) sum += v;
  return sum;
}

RatingDistribution RatingDistribution::renormalize() const {
  RatingDistribution out = *this;
  const double sum = total();
  if (sum <= 0.0) return out;
  for (double& v : out.p) v /= sum;
  out.renormalized = true;
  return out;
}

RatingDistribution RatingDistribution::pointMass(int rating) {
  RatingDistribution out;
  out.p[static_cast<std::size_t>(std::clamp(rating, 0, kRatingCount - 1))] = 1.0;
  out.coverage = 1.0;
  out.renormalized = true;
  return out;
}

RatingDistribution RatingDistribution::betaBinomial(double a, double b) {
  // pmf(k) = C(n,k) B(k+a, n-k+b) / B(a,b), computed in log space with lgamma for stability.
  const int n = kRatingCount - 1;
  auto logBeta = [](double x, double y) { return std::lgamma(x) + std::lgamma(y) - std::lgamma(x + y); };
  RatingDistribution out;
  const double base = logBeta(a, b);
  for (int k = 0; k <= n; ++k) {
    const double logChoose = std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0);
    out.p[static_cast<std::size_t>(k)] = std::exp(logChoose + logBeta(k + a, n - k + b) - base);
  }
  out = out.renormalize();  // removes rounding drift only
  out.coverage = 1.0;
  return out;
}

double bernoulliEntropyBits(double p) {
  p = std::clamp(p, 0.0, 1.0);
  if (p <= 0.0 || p >= 1.0) return 0.0;
  return -(p * std::log2(p) + (1.0 - p) * std::log2(1.0 - p));
}

}  // namespace cbtl::textpref
