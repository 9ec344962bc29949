// SignedRank.h — the one-sample Wilcoxon signed-rank test the paper reports per meal: do participants' Likert
// preferences for CBTL (1..5) lie above neutral (3)?
//
// Method, matching scipy.stats.wilcoxon(values - median, zero_method='wilcox', correction=True):
// - differences d = value - median; a zero difference says nothing about direction and is dropped before ranking
//   (Wilcoxon's original method, scipy's default zero_method='wilcox'); n counts the non-zero differences only.
// - |d| ranked 1..n, ties sharing their average rank; W+ sums the ranks of positive differences, W- of negative ones
//   (W+ + W- = n(n+1)/2).
// - Exact null distribution of W+ (every sign pattern equally likely, counted by dynamic programming over the integer
//   ranks) when n <= 50 and no two |d| tie; otherwise the normal approximation, mean n(n+1)/4, variance
//   n(n+1)(2n+1)/24 - sum(t^3 - t)/48 over the tie groups of size t, with a continuity correction of 0.5 toward the
//   mean. Ties make the ranks non-integer, which the exact enumeration cannot count; past 50 the counts would no
//   longer fit in 64 bits, and the approximation is excellent there anyway.
// - p-values: two-sided, and one-sided for the alternative "the values' median is greater than `median`".
// - z = (W+ - n(n+1)/4 - 0.5 sign(W+ - n(n+1)/4)) / sd, the same formula for both methods (for an exact test it is
//   only reported, not used for p): positive when the values lie above `median`. scipy's two-sided zstatistic is
//   -|z|. Effect size r = z / sqrt(n).
//
// n = 0 (no values, or all equal to `median`): nothing to test; `tested` is false, both p-values are 1, z and r 0.
// Every value and `median` must be finite, else std::invalid_argument.
#pragma once

#include <cstddef>
#include <vector>

namespace cbtl::app::study {

struct SignedRankResult {
  enum class Method { Exact, Normal };

  bool tested = false;  // false when n = 0: no non-zero difference, so no test
  Method method = Method::Exact;
  std::size_t n = 0;      // non-zero differences, the ones ranked
  std::size_t zeros = 0;  // differences dropped for being zero
  bool ties = false;      // some |d| share a rank
  double wPlus = 0, wMinus = 0;
  double pTwoSided = 1, pGreater = 1;
  double z = 0;
  double effectSize = 0;  // r = z / sqrt(n)
};

SignedRankResult signedRank(const std::vector<double>& values, double median);

}  // namespace cbtl::app::study
