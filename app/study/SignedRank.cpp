#include "app/study/SignedRank.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace cbtl::app::study {

namespace {

constexpr std::size_t kMaxExactN = 50;  // 2^50 sign patterns still count exactly in 64 bits (and in a double)

struct Ranking {
  std::vector<double> rank;  // of |d|, by position in d
  double tieTerm = 0;        // sum of t^3 - t over the tie groups
  bool ties = false;
};

Ranking rankAbsolute(const std::vector<double>& d) {
  std::vector<std::size_t> order(d.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return std::abs(d[a]) < std::abs(d[b]); });
  Ranking out{std::vector<double>(d.size()), 0, false};
  for (std::size_t start = 0; start < order.size();) {
    std::size_t end = start + 1;
    while (end < order.size() && std::abs(d[order[end]]) == std::abs(d[order[start]])) ++end;
    const double average = (static_cast<double>(start + 1) + static_cast<double>(end)) / 2;
    for (std::size_t k = start; k < end; ++k) out.rank[order[k]] = average;
    const auto t = static_cast<double>(end - start);
    if (end - start > 1) {
      out.ties = true;
      out.tieTerm += t * t * t - t;
    }
    start = end;
  }
  return out;
}

// counts[s] = how many of the 2^n sign patterns of ranks 1..n give W+ = s.
std::vector<std::uint64_t> rankSumCounts(std::size_t n) {
  std::vector<std::uint64_t> counts(n * (n + 1) / 2 + 1, 0);
  counts[0] = 1;
  std::size_t top = 0;
  for (std::size_t rank = 1; rank <= n; ++rank) {
    top += rank;
    for (std::size_t s = top; s >= rank; --s) counts[s] += counts[s - rank];
  }
  return counts;
}

// P(W+ >= w) and P(W+ <= w) under the null, w an integer rank sum.
void exactTails(std::size_t n, std::size_t w, double& upper, double& lower) {
  const std::vector<std::uint64_t> counts = rankSumCounts(n);
  std::uint64_t atLeast = 0, atMost = 0;
  for (std::size_t s = 0; s < counts.size(); ++s) {
    if (s >= w) atLeast += counts[s];
    if (s <= w) atMost += counts[s];
  }
  const double total = std::ldexp(1.0, static_cast<int>(n));
  upper = static_cast<double>(atLeast) / total;
  lower = static_cast<double>(atMost) / total;
}

double normalUpperTail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

}  // namespace

SignedRankResult signedRank(const std::vector<double>& values, double median) {
  if (!std::isfinite(median)) throw std::invalid_argument("signed-rank test: the median to test against is not finite");
  std::vector<double> d;
  SignedRankResult result;
  for (double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument("signed-rank test: a value is not finite");
    if (v - median == 0)
      ++result.zeros;
    else
      d.push_back(v - median);
  }
  result.n = d.size();
  if (d.empty()) return result;
  result.tested = true;

  const Ranking ranking = rankAbsolute(d);
  result.ties = ranking.ties;
  for (std::size_t i = 0; i < d.size(); ++i) (d[i] > 0 ? result.wPlus : result.wMinus) += ranking.rank[i];

  const auto n = static_cast<double>(result.n);
  const double mean = n * (n + 1) / 4;
  const double sd = std::sqrt(n * (n + 1) * (2 * n + 1) / 24 - ranking.tieTerm / 48);
  const double offset = result.wPlus - mean;
  const double correction = offset > 0 ? 0.5 : offset < 0 ? -0.5 : 0.0;
  result.z = (offset - correction) / sd;
  result.effectSize = result.z / std::sqrt(n);

  if (result.n <= kMaxExactN && !result.ties) {
    result.method = SignedRankResult::Method::Exact;
    double upper = 1, lower = 1;
    exactTails(result.n, static_cast<std::size_t>(std::llround(result.wPlus)), upper, lower);
    result.pGreater = upper;
    result.pTwoSided = std::min(1.0, 2 * std::min(upper, lower));
  } else {
    result.method = SignedRankResult::Method::Normal;
    result.pTwoSided = std::min(1.0, 2 * normalUpperTail(std::abs(result.z)));
    // One-sided, the continuity correction is always half a rank down: P(W+ >= w) ~ P(N >= w - 0.5).
    result.pGreater = normalUpperTail((offset - 0.5) / sd);
  }
  return result;
}

}  // namespace cbtl::app::study
