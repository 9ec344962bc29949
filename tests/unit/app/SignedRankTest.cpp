#include "app/study/SignedRank.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

// Reference values: scipy 1.10.1 (Debian 12's python3-scipy), each test's numbers printed by the command above them.
// The one-sample test is run on the differences d = values - median, zeros dropped as zero_method='wilcox' does;
// scipy's z is its zstatistic with the continuity correction: for W+ above its mean, alternative='greater' gives our
// z; below, the two-sided one does (scipy's two-sided zstatistic is -|z|).

namespace cbtl::app::study {
namespace {

using Method = SignedRankResult::Method;

constexpr double kExact = 1e-9;
constexpr double kNormal = 1e-6;

struct Reference {
  Method method;
  std::size_t n, zeros;
  double wPlus, pTwoSided, pGreater, z;
};

void expectReference(const SignedRankResult& r, const Reference& ref, double tolerance) {
  EXPECT_TRUE(r.tested);
  EXPECT_EQ(r.method, ref.method);
  EXPECT_EQ(r.n, ref.n);
  EXPECT_EQ(r.zeros, ref.zeros);
  if (ref.n <= 50) {
    EXPECT_EQ(r.ties, ref.method == Method::Normal);  // below 51, only ties make it normal
  }
  const double n = static_cast<double>(ref.n);
  EXPECT_DOUBLE_EQ(r.wPlus, ref.wPlus);
  EXPECT_DOUBLE_EQ(r.wMinus, n * (n + 1) / 2 - ref.wPlus);
  EXPECT_NEAR(r.pTwoSided, ref.pTwoSided, tolerance);
  EXPECT_NEAR(r.pGreater, ref.pGreater, tolerance);
  EXPECT_NEAR(r.z, ref.z, tolerance);
  EXPECT_NEAR(r.effectSize, ref.z / std::sqrt(n), tolerance);
}

// 1 - offset, 2 - offset, ..., n - offset.
std::vector<double> steps(int n, double offset) {
  std::vector<double> out;
  for (int i = 1; i <= n; ++i) out.push_back(i - offset);
  return out;
}

const std::vector<double> kLikert60{5, 4, 4, 3, 5, 2, 4, 5, 3, 4, 1, 5, 4, 4, 2, 5, 3, 4, 5, 4,
                                    3, 5, 4, 2, 4, 5, 5, 3, 4, 1, 4, 5, 2, 4, 3, 5, 4, 4, 5, 3,
                                    2, 4, 5, 4, 1, 5, 4, 3, 4, 5, 2, 4, 5, 4, 3, 4, 5, 1, 4, 5};

// Seven distinct differences: the exact distribution.
TEST(SignedRankTest, SmallSampleIsExact) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([1.5, 2.7, -0.4, 3.1, 0.8, -1.2, 2.2], dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 24.0 0.109375 0.0546875 1.6057930839841814
  // clang-format on
  const Reference ref{Method::Exact, 7, 0, 24.0, 0.109375, 0.0546875, 1.6057930839841814};
  expectReference(signedRank({1.5, 2.7, -0.4, 3.1, 0.8, -1.2, 2.2}, 0), ref, kExact);
}

// Mostly negative differences: z < 0, one-sided p near 1.
TEST(SignedRankTest, ValuesBelowTheMedianGiveASmallWPlus) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([-3.2, -1.1, 0.5, -2.4, -0.7, -4.1, 1.9, -2.8], dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='two-sided', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 5.0 0.078125 0.97265625 -1.750350105035012
  // clang-format on
  const Reference ref{Method::Exact, 8, 0, 5.0, 0.078125, 0.97265625, -1.750350105035012};
  expectReference(signedRank({-3.2, -1.1, 0.5, -2.4, -0.7, -4.1, 1.9, -2.8}, 0), ref, kExact);
}

// Tied |d| (2, 2 and 4, 4, 4, and 1 vs -1, 2 vs -2): average ranks, the normal approximation.
TEST(SignedRankTest, TiesUseTheNormalApproximationWithTieCorrection) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([1, 2, 2, 3, -1, 4, 4, 4, -2, 5], dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='approx', alternative='greater', **k).statistic), repr(w(d, method='approx', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 49.5 0.02749596793801716 0.01374798396900858 2.204403668159369
  // clang-format on
  const Reference ref{Method::Normal, 10, 0, 49.5, 0.02749596793801716, 0.01374798396900858, 2.204403668159369};
  expectReference(signedRank({1, 2, 2, 3, -1, 4, 4, 4, -2, 5}, 0), ref, kNormal);
}

// Three values equal to the median are dropped; the five others are distinct, so exact. (scipy 1.10 switches to the
// normal approximation whenever zeros are present, so the commands drop them first, as zero_method='wilcox' does.)
TEST(SignedRankTest, ZerosAreDroppedBeforeRanking) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([3, 5, 3, 1.5, 4.2, 3, 6.1, 2.4], dtype=float) - 3; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 11.0 0.4375 0.21875 0.8090398349558905
  // clang-format on
  const Reference ref{Method::Exact, 5, 3, 11.0, 0.4375, 0.21875, 0.8090398349558905};
  expectReference(signedRank({3, 5, 3, 1.5, 4.2, 3, 6.1, 2.4}, 3), ref, kExact);
}

// Zeros dropped, ties among the rest: normal.
TEST(SignedRankTest, ZerosAndTiesTogether) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([3, 4, 3, 2, 5, 3, 4, 1, 5, 4], dtype=float) - 3; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='approx', alternative='greater', **k).statistic), repr(w(d, method='approx', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 19.5 0.3858817586602541 0.19294087933012705 0.8671099695241199
  // clang-format on
  const Reference ref{Method::Normal, 7, 3, 19.5, 0.3858817586602541, 0.19294087933012705, 0.8671099695241199};
  expectReference(signedRank({3, 4, 3, 2, 5, 3, 4, 1, 5, 4}, 3), ref, kNormal);
}

// Ties with the values mostly below the median: the continuity correction moves z up toward 0.
TEST(SignedRankTest, TiesBelowTheMedian) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([1, 2, 2, 1, 3, 1, 4, 2, 1, 5], dtype=float) - 3; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='approx', alternative='greater', **k).statistic), repr(w(d, method='approx', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='two-sided', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 9.5 0.1281465612656797 0.9498258767688547 -1.5214515486254614
  // clang-format on
  const Reference ref{Method::Normal, 9, 1, 9.5, 0.1281465612656797, 0.9498258767688547, -1.5214515486254614};
  expectReference(signedRank({1, 2, 2, 1, 3, 1, 4, 2, 1, 5}, 3), ref, kNormal);
}

// Every difference positive: p(greater) = 2^-6.
TEST(SignedRankTest, AllPositiveGivesTheSmallestExactPValue) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([0.5, 1.1, 2.3, 3.7, 4.2, 5.9], dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 21.0 0.03125 0.015625 2.096569673443837
  // clang-format on
  const Reference ref{Method::Exact, 6, 0, 21.0, 0.03125, 0.015625, 2.096569673443837};
  expectReference(signedRank({0.5, 1.1, 2.3, 3.7, 4.2, 5.9}, 0), ref, kExact);
}

// n = 1: p(greater) = 1/2, two-sided 1.
TEST(SignedRankTest, OneValueCannotBeSignificant) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([4], dtype=float) - 3; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 1.0 1.0 0.5 0.0
  // clang-format on
  const Reference ref{Method::Exact, 1, 0, 1.0, 1.0, 0.5, 0.0};
  expectReference(signedRank({4}, 3), ref, kExact);
}

// n = 50, the largest exact case: 1 - 20.25, ..., 50 - 20.25 (no |d| ties: .75 vs .25).
TEST(SignedRankTest, FiftyDistinctDifferencesAreStillExact) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array(np.arange(1, 51) - 20.25, dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='exact', alternative='greater', **k).statistic), repr(w(d, method='exact', **k).pvalue), repr(w(d, method='exact', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 875.0 0.02122367163684835 0.010611835818424176 2.287827045851535
  // clang-format on
  const Reference ref{Method::Exact, 50, 0, 875.0, 0.02122367163684835, 0.010611835818424176, 2.287827045851535};
  expectReference(signedRank(steps(50, 20.25), 0), ref, kExact);
}

// n = 55 without ties: normal.
TEST(SignedRankTest, FiftyOneAndMoreUseTheNormalApproximation) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array(np.arange(1, 56) - 20.25, dtype=float) - 0; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='approx', alternative='greater', **k).statistic), repr(w(d, method='approx', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 1140.0 0.0019623401550822083 0.0009811700775411041 3.095873565640744
  // clang-format on
  const Reference ref{Method::Normal, 55, 0, 1140.0, 0.0019623401550822083, 0.0009811700775411041, 3.095873565640744};
  expectReference(signedRank(steps(55, 20.25), 0), ref, kNormal);
}

// The study's case: 60 ratings in 1..5 against 3 (9 neutral ones dropped, massive ties): normal.
TEST(SignedRankTest, SixtyLikertAnswersAgainstNeutral) {
  // clang-format off
  // python3 -c "import numpy as np; from scipy.stats import wilcoxon as w; d = np.array([5, 4, 4, 3, 5, 2, 4, 5, 3, 4, 1, 5, 4, 4, 2, 5, 3, 4, 5, 4, 3, 5, 4, 2, 4, 5, 5, 3, 4, 1, 4, 5, 2, 4, 3, 5, 4, 4, 5, 3, 2, 4, 5, 4, 1, 5, 4, 3, 4, 5, 2, 4, 5, 4, 3, 4, 5, 1, 4, 5], dtype=float) - 3; d = d[d != 0]; k = dict(zero_method='wilcox', correction=True); print(repr(w(d, method='approx', alternative='greater', **k).statistic), repr(w(d, method='approx', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).pvalue), repr(w(d, method='approx', alternative='greater', **k).zstatistic))"
  // prints W+, two-sided p, one-sided p, z: 1074.0 6.971161989000083e-05 3.4855809945000416e-05 3.9772678712933156
  // clang-format on
  const Reference ref{Method::Normal, 51, 9, 1074.0, 6.971161989000083e-05, 3.4855809945000416e-05, 3.9772678712933156};
  expectReference(signedRank(kLikert60, 3), ref, kNormal);
}

// The largest exact case at its extreme: only one of the 2^50 sign patterns puts every rank on the positive side.
TEST(SignedRankTest, FiftyPositiveDifferencesCountEverySignPattern) {
  const SignedRankResult r = signedRank(steps(50, 0), 0);
  EXPECT_EQ(r.method, Method::Exact);
  EXPECT_DOUBLE_EQ(r.wPlus, 1275);
  EXPECT_DOUBLE_EQ(r.pGreater, std::ldexp(1.0, -50));
  EXPECT_DOUBLE_EQ(r.pTwoSided, std::ldexp(1.0, -49));
}

TEST(SignedRankTest, NoValuesMeanNoTest) {
  for (const std::vector<double>& values : {std::vector<double>{}, std::vector<double>{3, 3, 3}}) {
    const SignedRankResult r = signedRank(values, 3);
    EXPECT_FALSE(r.tested);
    EXPECT_EQ(r.n, 0u);
    EXPECT_EQ(r.zeros, values.size());
    EXPECT_EQ(r.method, Method::Exact);
    EXPECT_EQ(r.pTwoSided, 1);
    EXPECT_EQ(r.pGreater, 1);
    EXPECT_EQ(r.z, 0);
    EXPECT_EQ(r.effectSize, 0);
    EXPECT_EQ(r.wPlus + r.wMinus, 0);
  }
}

TEST(SignedRankTest, NonFiniteInputIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(signedRank({1, nan, 4}, 3), std::invalid_argument);
  EXPECT_THROW(signedRank({1, -inf}, 3), std::invalid_argument);
  EXPECT_THROW(signedRank({1, 2}, nan), std::invalid_argument);
  EXPECT_THROW(signedRank({1, 2}, inf), std::invalid_argument);
}

}  // namespace
}  // namespace cbtl::app::study
