// rt::Rng, the project's one generator: the engine is the standard's mt19937_64, every draw is the documented
// mapping of its raw words (checked against a std::mt19937_64 with the same seed), fixed sequences pin the
// algorithms down as regression tests, and over many draws the distributions have the right moments.
#include "runtime/approach/Experiment.h"
#include "runtime/core/Rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

using cbtl::rt::Rng;

namespace {

constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

TEST(Rng, EngineIsTheStandardMt19937_64) {
  // [rand.predef]: the 10000th consecutive invocation of a default-constructed mt19937_64 gives this value.
  Rng rng(std::mt19937_64::default_seed);
  std::uint64_t last = 0;
  for (int i = 0; i < 10000; ++i) last = rng.next();
  EXPECT_EQ(last, 9981545732273789042ULL);
  Rng reseeded(99);
  reseeded.next();
  reseeded.seed(std::mt19937_64::default_seed);
  std::mt19937_64 raw;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(reseeded.next(), raw());
}

TEST(Rng, UniformIsTheTop53BitsOfOneWord) {
  Rng rng(42);
  std::mt19937_64 raw(42);
  for (int i = 0; i < 1000; ++i) {
    const double u = rng.uniform();
    EXPECT_EQ(u, static_cast<double>(raw() >> 11) * 0x1.0p-53);
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
  }
}

TEST(Rng, UniformBetweenBoundsIsAffineInOneWord) {
  Rng rng(2026);
  std::mt19937_64 raw(2026);
  for (int i = 0; i < 1000; ++i) {
    const double x = rng.uniform(-1.0, 3.0);
    EXPECT_EQ(x, -1.0 + 4.0 * (static_cast<double>(raw() >> 11) * 0x1.0p-53));
    EXPECT_GE(x, -1.0);
    EXPECT_LT(x, 3.0);
  }
  EXPECT_EQ(rng.uniform(2.5, 2.5), 2.5);
  raw();
  EXPECT_EQ(rng.next(), raw());  // the degenerate draw still consumed exactly one word
}

TEST(Rng, IndexIsTheWordModuloN) {
  // For small n a rejected word has probability below n / 2^64, so the draws are word % n, one word each.
  Rng rng(5);
  std::mt19937_64 raw(5);
  for (std::size_t n : {1u, 2u, 3u, 7u, 10u, 1000u}) {
    for (int i = 0; i < 200; ++i) EXPECT_EQ(rng.index(n), raw() % n) << "n = " << n;
  }
}

TEST(Rng, UniformIntCoversBothBoundsAndWideSpans) {
  Rng rng(8);
  bool sawLo = false, sawHi = false;
  for (int i = 0; i < 2000; ++i) {
    const std::int64_t v = rng.uniformInt(-3, 3);
    ASSERT_GE(v, -3);
    ASSERT_LE(v, 3);
    sawLo = sawLo || v == -3;
    sawHi = sawHi || v == 3;
  }
  EXPECT_TRUE(sawLo);
  EXPECT_TRUE(sawHi);
  EXPECT_EQ(rng.uniformInt(4, 4), 4);
  // The full int64 range (span 2^64 wraps to 0) is the raw word.
  Rng full(9);
  std::mt19937_64 raw(9);
  EXPECT_EQ(full.uniformInt(INT64_MIN, INT64_MAX), static_cast<std::int64_t>(raw()));
  // Bounds of opposite sign beyond 2^62 (hi - lo overflows int64).
  for (int i = 0; i < 100; ++i) {
    const std::int64_t v = full.uniformInt(INT64_MIN / 2 - 5, INT64_MAX / 2 + 5);
    EXPECT_GE(v, INT64_MIN / 2 - 5);
    EXPECT_LE(v, INT64_MAX / 2 + 5);
  }
}

TEST(Rng, FixedSequencesForFixedSeeds) {
  // Regression values of the documented algorithms (engine words, modulo with rejection, Fisher-Yates from the
  // back, Box-Muller's cosine branch); a change here changes every stream of the project.
  Rng a(7);
  std::vector<std::size_t> indices;
  for (int i = 0; i < 12; ++i) indices.push_back(a.index(6));
  EXPECT_EQ(indices, (std::vector<std::size_t>{3, 0, 0, 0, 1, 0, 3, 4, 3, 2, 4, 3}));
  Rng b(1);
  EXPECT_EQ(b.permutation(9), (std::vector<std::size_t>{8, 3, 2, 1, 7, 0, 4, 6, 5}));
  // std::log and std::cos may differ in the last bits between C math libraries.
  Rng c(3);
  const double expected[] = {0.36059248994300253, -0.58446613806844594, -0.69340574083840045, -0.69041829772727281};
  for (double e : expected) EXPECT_NEAR(c.normal(), e, 1e-12);
}

TEST(Rng, NormalIsBoxMullerOverTwoUniforms) {
  Rng rng(11), replay(11);
  for (int i = 0; i < 100; ++i) {
    const double u1 = replay.uniform(), u2 = replay.uniform();  // u1 = 0 has probability 2^-53
    EXPECT_EQ(rng.normal(), std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2));
  }
  Rng scaled(12), unit(12);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(scaled.normal(-2.0, 0.5), -2.0 + 0.5 * unit.normal());
  EXPECT_EQ(scaled.normal(1.5, 0.0), 1.5);
}

TEST(Rng, UniformHasTheMomentsOfU01) {
  Rng rng(123);
  const int n = 200000;
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    sum += u;
    sumSq += u * u;
  }
  const double mean = sum / n, variance = sumSq / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 0.005);  // standard error 0.00065
  EXPECT_NEAR(variance, 1.0 / 12.0, 0.002);
}

TEST(Rng, IndexHitsEveryValueEquallyOften) {
  Rng rng(77);
  const std::size_t n = 7;
  const int draws = 70000;
  std::vector<int> counts(n, 0);
  for (int i = 0; i < draws; ++i) ++counts[rng.index(n)];
  for (std::size_t k = 0; k < n; ++k) EXPECT_NEAR(counts[k], draws / 7, 500) << "value " << k;  // sd about 93
}

TEST(Rng, NormalHasTheMomentsOfAStandardNormal) {
  Rng rng(321);
  const int n = 200000;
  double sum = 0, sumSq = 0;
  int withinOneSd = 0;
  for (int i = 0; i < n; ++i) {
    const double z = rng.normal();
    sum += z;
    sumSq += z * z;
    withinOneSd += std::abs(z) < 1.0 ? 1 : 0;
  }
  const double mean = sum / n, variance = sumSq / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 0.015);      // standard error 0.0022
  EXPECT_NEAR(variance, 1.0, 0.025);  // standard error 0.0032
  EXPECT_NEAR(static_cast<double>(withinOneSd) / n, 0.6827, 0.006);
}

TEST(Rng, PermutationHoldsEveryElementOnce) {
  Rng rng(4);
  for (std::size_t n : {0u, 1u, 2u, 9u, 100u}) {
    std::vector<std::size_t> p = rng.permutation(n);
    ASSERT_EQ(p.size(), n);
    std::sort(p.begin(), p.end());
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(p[i], i) << "n = " << n;
  }
}

TEST(Rng, PermutationsOfThreeAreEquallyLikely) {
  Rng rng(5);
  std::map<std::vector<std::size_t>, int> counts;
  const int draws = 60000;
  for (int i = 0; i < draws; ++i) ++counts[rng.permutation(3)];
  ASSERT_EQ(counts.size(), 6u);
  for (const auto& [order, count] : counts) EXPECT_NEAR(count, draws / 6, 500);  // sd about 91
}

TEST(Rng, ShuffleAppliesThePermutationsSwaps) {
  std::vector<std::string> items = {"a", "b", "c", "d", "e", "f", "g"};
  const std::vector<std::string> original = items;
  Rng rng(6), same(6);
  rng.shuffle(items.begin(), items.end());
  const std::vector<std::size_t> p = same.permutation(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) EXPECT_EQ(items[i], original[p[i]]);
  std::vector<int> empty;
  rng.shuffle(empty.begin(), empty.end());
  EXPECT_TRUE(empty.empty());
}

TEST(Rng, SplitMix64MatchesTheReferenceSequence) {
  // The first outputs of SplitMix64 started at state 0: splitMix64(k * golden) is the (k+1)-th.
  EXPECT_EQ(cbtl::rt::splitMix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(cbtl::rt::splitMix64(kGolden), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(cbtl::rt::splitMix64(2 * kGolden), 0x06c45d188009454fULL);
  // The experiment's stream seeds are SplitMix64 at the stream's position; stream 0 is the Cooking shift seed.
  for (std::uint64_t seed : {0ULL, 1ULL, 42ULL}) {
    EXPECT_EQ(cbtl::approach::deriveSeed(seed, 0), cbtl::rt::splitMix64(seed));
    EXPECT_EQ(cbtl::approach::deriveSeed(seed, 3), cbtl::rt::splitMix64(seed + 3 * kGolden));
  }
}

}  // namespace
