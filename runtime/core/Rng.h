// Rng.h — the project's one random number generator: the engine, its draws and seed derivation.
//
// Every random choice in the project (solver, approaches, simulators, the robot world, the motion planner's
// samplers) draws from an Rng; one Rng per component, seeded from the run seed (splitMix64 derives
// independent seeds). The engine is std::mt19937_64, whose output sequence the standard fixes. The draws are
// written out here rather than taken from <random>'s distributions, whose mappings (like std::shuffle's
// algorithm) are implementation-defined: the same seed must give the same run with any standard library. Rng
// is deliberately not a UniformRandomBitGenerator (it has no operator()), so it cannot be handed to a
// <random> distribution or to std::shuffle by mistake; next() gives the raw words.
//
// The draws, with the engine words each consumes (the count is part of the contract: it fixes the streams):
//   next()              one raw 64-bit word.
//   uniform()           [0, 1): the word's top 53 bits times 2^-53 (every double of the form k·2^-53). One word.
//   uniform(lo, hi)     lo + (hi - lo)·uniform(), one word. In [lo, hi), except that the rounding of the
//                       product and sum can give hi itself for some bounds; callers that need hi excluded
//                       clamp. lo == hi gives lo.
//   uniformInt(lo, hi)  [lo, hi], both inclusive: word % span, rejecting words at or above the largest
//                       multiple of span not above 2^64 - 1 (so exactly uniform; the chance of a second word
//                       is below span / 2^64).
//   index(n)            uniformInt(0, n - 1).
//   coin(p)             uniform() < p. One word.
//   normal()            standard normal by the basic Box-Muller transform, cosine branch only:
//                       sqrt(-2 ln u1)·cos(2π u2) with u1 = uniform() redrawn while 0, then u2 = uniform();
//                       the sine partner is discarded, so each call is self-contained. Two words (rarely
//                       more). std::log and std::cos come from the C library, which is not required to round
//                       correctly: normal() may differ in the last bits between C math libraries.
//   normal(mean, sd)    mean + sd·normal().
//   shuffle(first,last) Fisher-Yates from the back: for i = n - 1 down to 1, swap element i with element
//                       index(i + 1). n - 1 index draws.
//   permutation(n)      0..n-1 in an order drawn by shuffle.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace cbtl::rt {

// SplitMix64's output for state x (x advanced by the golden-ratio increment, then the finaliser): a
// well-mixed 64-bit value, used to derive the seed of an independent stream from a run seed.
inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : engine_(seed) {}
  void seed(std::uint64_t s) { engine_.seed(s); }

  std::uint64_t next() { return engine_(); }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi) (hi possible through rounding, see above); precondition lo <= hi.
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi] (both inclusive); precondition lo <= hi.
  std::int64_t uniformInt(std::int64_t lo, std::int64_t hi) {
    // In unsigned arithmetic: hi - lo overflows int64 for bounds of opposite sign beyond 2^62.
    const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo) + 1;
    if (span == 0) return static_cast<std::int64_t>(engine_());
    // Rejection keeps the draw exactly uniform.
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % span;
    std::uint64_t r;
    do {
      r = engine_();
    } while (r >= limit);
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(lo) + r % span);
  }
  // Index in [0, n); precondition n > 0.
  std::size_t index(std::size_t n) { return static_cast<std::size_t>(uniformInt(0, static_cast<std::int64_t>(n) - 1)); }
  bool coin(double p = 0.5) { return uniform() < p; }
  // Standard normal (Box-Muller, the cosine branch).
  double normal() {
    double u1 = uniform();
    while (u1 <= 0) u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  // Normal with the given mean and standard deviation (stdDev >= 0).
  double normal(double mean, double stdDev) { return mean + stdDev * normal(); }
  // Puts [first, last) in a uniformly drawn order (Fisher-Yates, see above).
  template <std::random_access_iterator It>
  void shuffle(It first, It last) {
    for (auto n = last - first; n > 1; --n) {
      const auto j = static_cast<std::iter_difference_t<It>>(index(static_cast<std::size_t>(n)));
      std::iter_swap(first + (n - 1), first + j);
    }
  }
  // A uniformly drawn permutation of 0..n-1.
  std::vector<std::size_t> permutation(std::size_t n) {
    std::vector<std::size_t> v(n);
    std::iota(v.begin(), v.end(), std::size_t{0});
    shuffle(v.begin(), v.end());
    return v;
  }

  // The engine's whole state as text (the standard's textual form of std::mt19937_64), and back: a restored
  // Rng continues the exact sequence. restoreState returns false (the Rng unchanged) for text that is not a state.
  std::string saveState() const {
    std::ostringstream out;
    out << engine_;
    return out.str();
  }
  bool restoreState(const std::string& text) {
    std::istringstream in(text);
    std::mt19937_64 e;
    in >> e;
    if (in.fail()) return false;
    engine_ = e;
    return true;
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace cbtl::rt
