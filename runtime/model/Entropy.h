// Entropy.h — Bernoulli entropy in bits, the uncertainty CBTL's exploration maximizes.
#pragma once

#include <cmath>

namespace cbtl::model {

// H(p) = -(p log2 p + (1-p) log2(1-p)); 0 at p = 0 and p = 1, 1 bit at p = 0.5. p outside [0, 1] is clamped.
inline double bernoulliEntropyBits(double p) {
  if (!(p > 0.0) || !(p < 1.0)) return 0.0;
  return -(p * std::log2(p) + (1.0 - p) * std::log2(1.0 - p));
}

}  // namespace cbtl::model
