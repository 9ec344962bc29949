// RatingDistribution.h — the 11-bin rating object shared by every text-preference backend.
//
// The paper reads a rating r in 0..10 as "asked ten times, the user would say yes r times", so
// P(holds) = sum_r (r/10) p_r. Both backends produce this object: the LLM backend from next-token
// log-probabilities, the offline descriptor model from a Beta-Binomial predictive. `coverage` is the mass that
// fell on the 11 ratings before any renormalisation (1 for the offline model); when `renormalized` is false the
// bins may sum to less than 1 and the missing mass counts as rating 0, which is what the reference code does.
#pragma once

#include <array>

namespace cbtl::textpref {

inline constexpr int kRatingCount = 11;  // ratings 0..10

struct RatingDistribution {
  std::array<double, kRatingCount> p{};  // p[r] = probability of rating r, each in [0, 1]
  double coverage = 0.0;                 // sum of the raw rating probabilities, in [0, 1]
  bool renormalized = false;             // true when p was divided by coverage

  // sum_r (r/10) p[r], clamped to [0, 1].
  double expectedProbability() const;
  // Sum of the bins (1 after renormalisation, `coverage` otherwise).
  double total() const;

  // Divides every bin by their sum; a distribution without mass is left unchanged.
  RatingDistribution renormalize() const;
  // All mass on one rating (0..10): the degraded answer when only a digit is known.
  static RatingDistribution pointMass(int rating);
  // The Beta-Binomial(10, a, b) distribution, a > 0, b > 0. Its expected probability is a / (a + b).
  static RatingDistribution betaBinomial(double a, double b);
};

// Entropy in bits of a Bernoulli(p) variable; 0 at p = 0 or 1, 1 at p = 0.5. p is clamped to [0, 1].
double bernoulliEntropyBits(double p);

}  // namespace cbtl::textpref
