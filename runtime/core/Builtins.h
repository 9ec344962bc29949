// Builtins.h — the C++ side of the `extern fn` and `extern sampler` declarations of the standard library.
//
// A built-in reads its arguments as one concatenated run of doubles (each argument in its Values.h layout,
// in declaration order) and writes its result into `out`. Generic built-ins (e.g. distance<N>) learn N from
// the argument widths they are handed. Functions are pure. A sampler draws from the Rng it is given and
// returns false when it cannot produce a value (e.g. an empty range), so the solver can try another sampler.
//
// Binding is by name: a program that calls an extern the registry lacks is rejected before it runs, with
// the call's source location.
//
// Every call also receives a CallContext: the program's string table (text arguments are string ids) and
// the host, the per-program state some built-ins need (the robot world of robot/bind/WorldBuiltins.h).
// A registry that binds such built-ins carries its host; the Program adopts it. Built-ins of the prelude and
// geometry read neither.
#pragma once

#include "runtime/core/Rng.h"
#include "runtime/core/Values.h"

#include <cstddef>
#include <map>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace cbtl::sim {
class ExecutionModel;
}

namespace cbtl::rt {

// State that built-ins of one kind share (e.g. the robot world). Owned by the registry that binds them and
// then by the Program; used by one thread at a time, like the Program.
class BuiltinHost {
 public:
  virtual ~BuiltinHost() = default;
  // The world model that dry-runs plans and moves the built-ins' state from skill to skill
  // (runtime/sim/ExecutionModel.h); null when the host has none.
  virtual sim::ExecutionModel* executionModel() { return nullptr; }
};

struct CallContext {
  StringTable* strings = nullptr;  // mutable: text results (e.g. concatenation) are interned
  BuiltinHost* host = nullptr;
};

using FunctionImpl = void (*)(const CallContext& cx, std::span<const double> args,
                              std::span<const std::uint16_t> widths, std::span<double> out);
using SamplerImpl = bool (*)(const CallContext& cx, std::span<const double> args, std::span<const std::uint16_t> widths,
                             Rng& rng, std::span<double> out);

// text + text: the concatenation's string id (interned in cx.strings). Compiled for `+` on texts.
void concatTexts(const CallContext& cx, std::span<const double> args, std::span<const std::uint16_t> widths,
                 std::span<double> out);

class Builtins {
 public:
  // The prelude, geometry and text built-ins (std.prelude, std.geometry, std.text).
  static Builtins standard();

  // `readsHost`: the built-in reads the host's state (the robot world as the current stage shows it), so its
  // value depends on more than its arguments (solver/StagedPlan.h evaluates such calls in their skill's state).
  void addFunction(const std::string& name, FunctionImpl f, bool readsHost = false) {
    functions_[name] = f;
    if (readsHost) hostFunctions_.insert(f);
  }
  void addSampler(const std::string& name, SamplerImpl s, bool readsHost = false) {
    samplers_[name] = s;
    if (readsHost) hostSamplers_.insert(s);
  }
  bool readsHost(FunctionImpl f) const { return hostFunctions_.count(f) != 0; }
  bool readsHost(SamplerImpl s) const { return hostSamplers_.count(s) != 0; }
  FunctionImpl function(const std::string& name) const;
  SamplerImpl sampler(const std::string& name) const;
  std::vector<std::string> functionNames() const;
  std::vector<std::string> samplerNames() const;

  // The host the bound built-ins expect in CallContext::host (null when none needs one).
  void setHost(std::shared_ptr<BuiltinHost> host) { host_ = std::move(host); }
  const std::shared_ptr<BuiltinHost>& host() const { return host_; }

 private:
  std::shared_ptr<BuiltinHost> host_;
  std::map<std::string, FunctionImpl> functions_;
  std::map<std::string, SamplerImpl> samplers_;
  std::set<FunctionImpl> hostFunctions_;
  std::set<SamplerImpl> hostSamplers_;
};

}  // namespace cbtl::rt
