// Rng.h — the runtime's random number generator.
//
// One Rng per component, seeded from the run seed. The draws are written out here rather than taken from
// <random>'s distributions, whose outputs are implementation-defined: the same seed must give the same run
// with any standard library.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

namespace cbtl::rt {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : engine_(seed) {}
  void seed(std::uint64_t s) { engine_.seed(s); }

  std::uint64_t next() { return engine_(); }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
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
  // Standard normal (Box-Muller, one of the pair).
  double normal() {
    double u1 = uniform();
    while (u1 <= 0) u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace cbtl::rt
