// RuntimeSupport.h — what `cbtl run` and `cbtl solve` share: loading a .cbtl file for execution with its
// errors printed, and the domain simulators by name.
#pragma once

#include "DomainRegistry.h"
#include "Experiment.h"
#include "LoadedProgram.h"
#include "Solver.h"

#include <fmt/core.h>

#include <memory>
#include <string>

namespace cbtl::cli {

// Loads FILE; prints its diagnostics to stderr and returns nullptr when it cannot run.
inline std::unique_ptr<approach::LoadedProgram> loadForRun(const std::string& command, const std::string& path,
                                                           const std::string& stdlibDir) {
  auto lp = approach::LoadedProgram::load(path, stdlibDir);
  if (!lp->ok()) {
    fmt::print(stderr, "{}", lp->errors());
    fmt::print(stderr, "cbtl {}: '{}' cannot be run\n", command, path);
    return nullptr;
  }
  return lp;
}

inline approach::SimulatorFactory simulatorFactory(const std::string& domain) {
  return [domain](const sim::SimulatorOptions& options, std::uint64_t seed) {
    return domains::createSimulator(domain, options, seed);
  };
}

inline void addSolverOptions(CLI::App* cmd, solver::SolverOptions& o) {
  cmd->add_option("--max-iters", o.maxIters, "solver iterations per CSP")->capture_default_str();
  cmd->add_option("--num-improvements", o.numImprovements, "stop after this many improvements (N_improve)")->capture_default_str();
  cmd->add_option("--max-improvement-attempts", o.maxImprovementAttempts,
                  "stop this many iterations after the first solution")->capture_default_str();
  cmd->add_option("--memory-size", o.memorySize, "remembered satisfying values per constraint")->capture_default_str();
}

}  // namespace cbtl::cli
