// Builtins.h — the C++ side of the `extern fn` and `extern sampler` declarations of the standard library.
//
// A built-in reads its arguments as one concatenated run of doubles (each argument in its Values.h layout,
// in declaration order) and writes its result into `out`. Generic built-ins (e.g. distance<N>) learn N from
// the argument widths they are handed. Functions are pure. A sampler draws from the Rng it is given and
// returns false when it cannot produce a value (e.g. an empty range), so the solver can try another sampler.
//
// Binding is by name: a program that calls an extern the registry lacks is rejected before it runs, with
// the call's source location.
#pragma once

#include "Rng.h"

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace cbtl::rt {

using FunctionImpl = void (*)(std::span<const double> args, std::span<const std::uint16_t> widths, std::span<double> out);
using SamplerImpl = bool (*)(std::span<const double> args, std::span<const std::uint16_t> widths, Rng& rng,
                             std::span<double> out);

class Builtins {
 public:
  // The prelude and geometry built-ins (std.prelude, std.geometry).
  static Builtins standard();

  void addFunction(const std::string& name, FunctionImpl f) { functions_[name] = f; }
  void addSampler(const std::string& name, SamplerImpl s) { samplers_[name] = s; }
  FunctionImpl function(const std::string& name) const;
  SamplerImpl sampler(const std::string& name) const;
  std::vector<std::string> functionNames() const;
  std::vector<std::string> samplerNames() const;

 private:
  std::map<std::string, FunctionImpl> functions_;
  std::map<std::string, SamplerImpl> samplers_;
};

}  // namespace cbtl::rt
