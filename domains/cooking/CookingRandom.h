// CookingRandom.h — the uniform draws of the Cooking simulator, identical on every standard library.
//
// std::mt19937_64's output sequence is fixed by the standard, but std::uniform_real_distribution's mapping of
// it is not; these helpers map the raw 64-bit words themselves (the top 53 bits make one double in [0, 1)),
// so a seed gives the same stock, the same shifts and the same unsatisfiable picks with libstdc++ and libc++.
// Every helper consumes exactly one word of the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>

namespace cbtl::domains::cooking {

using Rng = std::mt19937_64;

// A double in [0, 1) with 53 random bits.
inline double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// lo + (hi - lo) * u with u in [0, 1): a value in [lo, hi] (hi itself only through rounding, never for lo == hi).
inline double uniformReal(Rng& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

// An index in [0, n); n must be positive.
inline std::size_t uniformIndex(Rng& rng, std::size_t n) {
  const auto i = static_cast<std::size_t>(uniform01(rng) * static_cast<double>(n));
  return i < n ? i : n - 1;  // u * n can round up to n for huge n; keep the index in range
}

// SplitMix64 finaliser: derives an independent seed for a second stream from a run seed.
inline std::uint64_t mixSeed(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace cbtl::domains::cooking
