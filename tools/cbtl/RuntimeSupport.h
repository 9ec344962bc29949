// RuntimeSupport.h — what `cbtl run` and `cbtl solve` share: loading a .cbtl file for execution with its
// errors printed, the domain simulators by name, and the text-preference backend of `model text(...)` factors.
#pragma once

#include "DomainRegistry.h"
#include "Experiment.h"
#include "LoadedProgram.h"
#include "Solver.h"

#include "textpref/TextBackend.h"

#include <fmt/core.h>

#include <map>
#include <memory>
#include <optional>
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
  static const std::map<std::string, solver::MemoryPolicy> policies = {
      {"checks", solver::MemoryPolicy::EverySatisfiedCheck}, {"solutions", solver::MemoryPolicy::Solutions}};
  cmd->add_option("--memory", o.memoryPolicy,
                  "what the solver remembers: checks (every satisfied constraint check, as the reference) | solutions")
      ->transform(CLI::CheckedTransformer(policies, CLI::ignore_case))
      ->default_str("checks");
}

// `--text-backend offline|openai`, `--llm-base-url`, `--llm-model`: which model text factors use. The offline
// descriptor model is the default (no network, no key). The language-model backend reads its key from the
// environment variable OPENAI_API_KEY at each request (never printed), keeps its response cache in memory, and
// talks to any OpenAI-compatible server (docs/textpref.md).
struct TextBackendArgs {
  std::string backend = "offline";
  std::string baseUrl, model;
};

inline void addTextBackendOptions(CLI::App* cmd, TextBackendArgs& a) {
  cmd->add_option("--text-backend", a.backend, "model of text factors: offline (descriptor model, no network) | openai")
      ->capture_default_str();
  cmd->add_option("--llm-base-url", a.baseUrl, "OpenAI-compatible server for --text-backend openai (default: api.openai.com)");
  cmd->add_option("--llm-model", a.model, "language model for --text-backend openai (default: gpt-4o-mini)");
}

// The backend the options ask for, or nullopt after printing a usage error. A null backend is the offline default.
inline std::optional<std::shared_ptr<const textpref::TextBackend>> makeTextBackend(const std::string& command,
                                                                                   const TextBackendArgs& a) {
  if (a.backend == "offline") {
    if (!a.baseUrl.empty() || !a.model.empty()) {
      fmt::print(stderr, "cbtl {}: error: --llm-base-url and --llm-model need --text-backend openai\n", command);
      return std::nullopt;
    }
    return std::shared_ptr<const textpref::TextBackend>();
  }
  if (a.backend != "openai") {
    fmt::print(stderr, "cbtl {}: error: unknown --text-backend '{}' (offline, openai)\n", command, a.backend);
    return std::nullopt;
  }
  textpref::TextBackendConfig config;
  config.kind = textpref::BackendKind::OpenAiCompatible;
  if (!a.baseUrl.empty()) config.chat.baseUrl = a.baseUrl;
  if (!a.model.empty()) config.chat.model = a.model;
  auto warn = [command](const std::string& message) { fmt::print(stderr, "cbtl {}: warning: {}\n", command, message); };
  return std::make_shared<const textpref::TextBackend>(std::move(config), warn);
}

}  // namespace cbtl::cli
