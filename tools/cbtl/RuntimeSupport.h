// RuntimeSupport.h — what `cbtl run`, `cbtl experiment` and `cbtl solve` share: the trial options, loading a .cbtl file
// (or the JSON graph `cbtlc emit --format json` wrote from one, app/LoadedProgram.h) for execution with its errors
// printed, the domain simulators by name, and the text-preference backend of `model text(...)` factors.
#pragma once

#include "app/DomainSolverOptions.h"
#include "app/LoadedProgram.h"
#include "app/RunFailures.h"
#include "app/SimulatorFacts.h"
#include "app/SimulatorSource.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"
#include "runtime/solver/Solver.h"
#include "tools/cbtl/OptionChecks.h"

#include "runtime/textpref/TextBackend.h"

#include <fmt/core.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace cbtl::cli {

// Loads FILE; prints its diagnostics to stderr and returns nullptr when it cannot run.
inline std::unique_ptr<app::LoadedProgram> loadForRun(const std::string& command, const std::string& path,
                                                      const std::string& stdlibDir) {
  auto lp = app::LoadedProgram::load(path, stdlibDir);
  if (!lp->ok()) {
    // A file that cannot be read is one error, said once with the command; diagnostics get the summary line.
    const std::string& errors = lp->errors();
    if (errors.rfind("error: cannot read file", 0) == 0 && errors.find('\n') + 1 == errors.size()) {
      fmt::print(stderr, "cbtl {}: {}", command, errors);
      return nullptr;
    }
    fmt::print(stderr, "{}", errors);
    fmt::print(stderr, "cbtl {}: '{}' cannot be run\n", command, path);
    return nullptr;
  }
  return lp;
}

// `--simulator CMD` and `--simulator-timeout-ms MS`: run against an external simulator program
// (docs/simulator-protocol.md) instead of the program's `simulator` line or the in-process domain.
struct ExternalSimulatorArgs {
  std::string command;
  int timeoutMs = 30000;
};

inline void addExternalSimulatorOptions(CLI::App* cmd, ExternalSimulatorArgs& a) {
  cmd->add_option("--simulator", a.command,
                  "run against this simulator program (a shell command speaking the external simulator protocol; "
                  "overrides the program's `simulator` line)");
  cmd->add_option("--simulator-timeout-ms", a.timeoutMs,
                  "the longest wait for one answer of an external simulator, in ms (1..3600000)")
      ->capture_default_str()
      ->check(CLI::Range(1, 3600000));
}

// The simulators of the program: the external one the options or the program name, else its in-process domain.
inline approach::SimulatorFactory simulatorFactory(const app::LoadedProgram& lp, const ExternalSimulatorArgs& a) {
  return app::simulatorFactory(lp, app::externalSimulator(lp, a.command, a.timeoutMs));
}

// The competence lines of a run's or an experiment's summary (approach/Experiment.h Competence).
inline void printCompetence(const approach::Competence& train, const approach::Competence& eval) {
  for (const auto& [name, c] : {std::pair{"training", &train}, std::pair{"evaluation", &eval}}) {
    fmt::print(
        "{}: {}/{} requests solved within budget ({:.1f} %), {}/{} solved plans executed without a failed "
        "action ({:.1f} %), {} dry-run mismatches, {} caregiver resets\n",
        name, c->solved, c->requests, 100 * c->solvedRate(), c->executed, c->executed + c->failed,
        100 * c->executedRate(), c->dryRunMismatches, c->caregiverResets);
  }
}

// Solver options as given on the command line; a budget not given is the domain's (domains::solverBudgets).
struct SolverArgs {
  std::optional<std::uint64_t> maxIters, numImprovements, maxImprovementAttempts;
  std::size_t memorySize = 100;
  solver::MemoryPolicy memoryPolicy = solver::MemoryPolicy::EverySatisfiedCheck;
};

inline void addSolverOptions(CLI::App* cmd, SolverArgs& o) {
  cmd->add_option("--max-iters", o.maxIters,
                  "solver iterations per CSP (default: the domain's; Cooking 100000, robot "
                  "domains 2500)")
      ->check(unsignedIn(1));
  cmd->add_option("--num-improvements", o.numImprovements,
                  "stop after this many improvements (N_improve; 0: the first solution; default: the domain's, 500)")
      ->check(unsignedIn(0));
  cmd->add_option("--max-improvement-attempts", o.maxImprovementAttempts,
                  "stop this many iterations after the first solution (default: the domain's; Cooking 10000, robot "
                  "domains 100)")
      ->check(unsignedIn(0));
  cmd->add_option("--memory-size", o.memorySize, "remembered satisfying values per constraint")
      ->capture_default_str()
      ->check(unsignedIn(1));
  static const std::map<std::string, solver::MemoryPolicy> policies = {
      {"checks", solver::MemoryPolicy::EverySatisfiedCheck}, {"solutions", solver::MemoryPolicy::Solutions}};
  cmd->add_option("--memory", o.memoryPolicy,
                  "what the solver remembers: checks (every satisfied constraint check, as the reference) | solutions")
      ->transform(CLI::CheckedTransformer(policies, CLI::ignore_case))
      ->default_str("checks");
}

// The solver options for a program of `domain`: what the command line gave, the domain's budgets otherwise.
inline solver::SolverOptions solverOptionsFor(const SolverArgs& a, const std::string& domain) {
  solver::SolverOptions o = app::domainSolverOptions(domain);
  o.maxIters = a.maxIters.value_or(o.maxIters);
  o.numImprovements = a.numImprovements.value_or(o.numImprovements);
  o.maxImprovementAttempts = a.maxImprovementAttempts.value_or(o.maxImprovementAttempts);
  o.memorySize = a.memorySize;
  o.memoryPolicy = a.memoryPolicy;
  return o;
}

// `--text-backend offline|openai`, `--llm-base-url`, `--llm-model`: which model text factors use. The offline
// descriptor model is the default (no network, no key). The language-model backend reads its key from the
// environment variable OPENAI_API_KEY at each request (never printed: server messages are redacted), keeps its
// response cache in memory, and talks to any OpenAI-compatible server (docs/textpref.md).
// Fault bounds (language-model backend only; -1 = not given, the backend's default):
//   --llm-timeout-ms T  whole-request timeout per attempt, 1..3600000 (default 60000; connect timeout min(5000, T))
//   --llm-attempts N    attempts per request, retries included, 1..100 (default 5)
//   --llm-breaker N     open the circuit breaker after N consecutive server failures (no answer, HTTP 408, 429,
//                       5xx), 0..1000 (default 3; 0 = never): the server is then not called for the rest of the
//                       command, ratings fall back
//   --llm-retry-budget N          retries per run, all requests together, 0..1000000 (default 100)
//   --llm-retry-wait-ms T         total wait before retries per run, 0..86400000 ms (default 300000)
//   --llm-max-retry-after-ms T    cap of a server's Retry-After, 0..3600000 ms (default 10000)
// (textpref/RetryBudget.h: once either budget is spent, no request of the run is retried.)
// Out-of-range values are usage errors (exit 2) naming the option.
// On a terminal (stderr is a tty) failed attempts are also reported live, at most a line per 5 s
// (textpref/FaultProgress.h); piped output only gets the breaker's one-line notice.
struct TextBackendArgs {
  std::string backend = "offline";
  std::string baseUrl, model;
  long timeoutMs = -1, retryWaitMs = -1, maxRetryAfterMs = -1;
  int attempts = -1, breaker = -1, retryBudget = -1;
};

inline void addTextBackendOptions(CLI::App* cmd, TextBackendArgs& a) {
  cmd->add_option("--text-backend", a.backend, "model of text factors: offline (descriptor model, no network) | openai")
      ->capture_default_str();
  cmd->add_option("--llm-base-url", a.baseUrl,
                  "OpenAI-compatible server for --text-backend openai (default: api.openai.com)");
  cmd->add_option("--llm-model", a.model, "language model for --text-backend openai (default: gpt-4o-mini)");
  cmd->add_option("--llm-timeout-ms", a.timeoutMs,
                  "per-request timeout in ms for --text-backend openai (default 60000)")
      ->check(CLI::Range(1L, 3600000L));
  cmd->add_option("--llm-attempts", a.attempts, "attempts per request, retries included, >= 1 (default 5)")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--llm-breaker", a.breaker,
                  "stop calling the server after N consecutive failures: no answer, HTTP 408, 429 or 5xx (default 3, "
                  "0 = never)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--llm-retry-budget", a.retryBudget,
                  "retries per run, all requests together; once spent, no request is retried (default 100)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--llm-retry-wait-ms", a.retryWaitMs,
                  "total wait before retries per run in ms; once spent, no request is retried (default 300000)")
      ->check(CLI::Range(0L, 86400000L));
  cmd->add_option("--llm-max-retry-after-ms", a.maxRetryAfterMs,
                  "longest wait a server's Retry-After gets, in ms (default 10000)")
      ->check(CLI::Range(0L, 3600000L));
}

// The backend the options ask for, or nullopt after printing a usage error. A null backend is the offline default.
inline std::optional<std::shared_ptr<const textpref::TextBackend>> makeTextBackend(const std::string& command,
                                                                                   const TextBackendArgs& a) {
  if (a.backend == "offline") {
    const char* openaiOnly = !a.baseUrl.empty()       ? "--llm-base-url"
                             : !a.model.empty()       ? "--llm-model"
                             : a.timeoutMs >= 0       ? "--llm-timeout-ms"
                             : a.attempts >= 0        ? "--llm-attempts"
                             : a.breaker >= 0         ? "--llm-breaker"
                             : a.retryBudget >= 0     ? "--llm-retry-budget"
                             : a.retryWaitMs >= 0     ? "--llm-retry-wait-ms"
                             : a.maxRetryAfterMs >= 0 ? "--llm-max-retry-after-ms"
                                                      : nullptr;
    if (openaiOnly != nullptr) {
      fmt::print(stderr, "cbtl {}: error: {} needs --text-backend openai\n", command, openaiOnly);
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
  if (a.timeoutMs >= 0) {
    config.chat.requestTimeoutMs = a.timeoutMs;
    config.chat.connectTimeoutMs = std::min(config.chat.connectTimeoutMs, a.timeoutMs);
  }
  if (a.attempts >= 0) config.chat.retry.maxAttempts = a.attempts;
  if (a.breaker >= 0) config.breakerThreshold = a.breaker;
  if (a.retryBudget >= 0) config.retryBudget.retries = a.retryBudget;
  if (a.retryWaitMs >= 0) config.retryBudget.waitMs = a.retryWaitMs;
  if (a.maxRetryAfterMs >= 0) config.chat.retry.maxRetryAfterMs = a.maxRetryAfterMs;
  auto warn = [command](const std::string& message) { fmt::print(stderr, "cbtl {}: warning: {}\n", command, message); };
  // Live fault lines only for a person at a terminal: tests and logs see the same output as before.
  std::shared_ptr<textpref::FaultProgress> progress;
  if (::isatty(STDERR_FILENO) != 0)
    progress = std::make_shared<textpref::FaultProgress>(
        [command](const std::string& line) { fmt::print(stderr, "cbtl {}: {}\n", command, line); });
  return std::make_shared<const textpref::TextBackend>(std::move(config), warn, textpref::realSleep(),
                                                       std::move(progress));
}

// Prints what the language model's failures cost a run (FaultReport::summary()); nothing when there were none.
inline void printLlmFaults(std::FILE* out, const textpref::FaultReport& faults) {
  if (faults.any()) fmt::print(out, "{}", faults.summary());
}

// The options of one trial of the experiment protocol, shared by `cbtl run` and `cbtl experiment`.
struct TrialArgs {
  std::string file, task, nonstationary = "none", stdlibDir;
  std::int64_t steps = 10000, evalEvery = 100, maxEvalSteps = 100, shiftEvery = 3000, periodicEvery = 1000;
  std::int64_t participant = -1;
  int evalTasks = 10;
  double epsilon = 0.5, unsatisfiable = 0;
  double maxFailureRate = app::kDefaultMaxFailureRate;  // not part of a trial: the command's verdict (RunFailures.h)
  bool replan = false, noMotionRecord = false;
  SolverArgs solver;
  TextBackendArgs text;
  ExternalSimulatorArgs external;
};

// Ranges: --max-failure-rate in [0, 1]; --steps >= 0; --eval-every, --eval-tasks, --max-eval-steps, --shift-every,
// --periodic-reset-every >= 1;
// --epsilon and --unsatisfiable-stock in [0, 1]. A value outside is a usage error (exit 2) naming the option.
inline void addTrialOptions(CLI::App* cmd, TrialArgs& a) {
  cmd->add_option("file", a.file, "the domain's .cbtl file, or its graph from `cbtlc emit --format json`")->required();
  cmd->add_option("--steps", a.steps, "training steps")->capture_default_str()->check(integerIn(0));
  cmd->add_option("--eval-every", a.evalEvery, "evaluate every K steps")->capture_default_str()->check(integerIn(1));
  cmd->add_option("--eval-tasks", a.evalTasks, "held-out tasks per evaluation")
      ->capture_default_str()
      ->check(integerIn(1, std::numeric_limits<int>::max()));
  cmd->add_option("--max-eval-steps", a.maxEvalSteps, "step limit of one evaluation episode")
      ->capture_default_str()
      ->check(integerIn(1));
  cmd->add_option("--task", a.task, "task to run (default: the first)");
  cmd->add_flag("--replan", a.replan, "when the full CSP is unsatisfiable, replan without personalized constraints");
  cmd->add_flag("--no-motion-record", a.noMotionRecord,
                "do not write motions.jsonl, the record of what the robot did (`cbtl audit` re-checks it)");
  cmd->add_option("--epsilon", a.epsilon, "epsilon-greedy's exploration probability")
      ->capture_default_str()
      ->check(realIn(0, 1));
  cmd->add_option("--nonstationary", a.nonstationary,
                  "shift the user's preferences: none | no-adapt | user-reset | periodic-reset")
      ->capture_default_str();
  cmd->add_option("--shift-every", a.shiftEvery, "steps between preference shifts")
      ->capture_default_str()
      ->check(integerIn(1));
  cmd->add_option("--periodic-reset-every", a.periodicEvery, "steps between model resets (periodic-reset)")
      ->capture_default_str()
      ->check(integerIn(1));
  cmd->add_option("--unsatisfiable-stock", a.unsatisfiable,
                  "probability that a restock cannot satisfy the user (Cooking)")
      ->capture_default_str()
      ->check(realIn(0, 1));
  cmd->add_option("--participant", a.participant,
                  "simulated user: the domain's N-th drawn participant, with their own preferences (Feeding; -1: the "
                  "default user)")
      ->capture_default_str()
      ->check(integerIn(-1));
  cmd->add_option("--max-failure-rate", a.maxFailureRate,
                  "above this share of failed requests (unsolved, or failed in execution) in training or evaluation, "
                  "warn and exit 3; 1 accepts any")
      ->capture_default_str()
      ->check(realIn(0, 1));
  cmd->add_option("--stdlib", a.stdlibDir, "standard library folder (default: embedded; not used by an emitted graph)");
  addSolverOptions(cmd, a.solver);
  addTextBackendOptions(cmd, a.text);
  addExternalSimulatorOptions(cmd, a.external);
}

// Fills everything but the approach, seed and outputs; false after printing a usage error.
inline bool configureTrial(const std::string& command, const TrialArgs& a, approach::ExperimentConfig& c) {
  c.recordMotions = !a.noMotionRecord;
  if (a.nonstationary != "none") {
    const auto mode = approach::parseAdaptation(a.nonstationary);
    if (!mode) {
      fmt::print(stderr,
                 "cbtl {}: error: unknown --nonstationary mode '{}' (none, no-adapt, user-reset, periodic-reset)\n",
                 command, a.nonstationary);
      return false;
    }
    c.nonstationary = true;
    c.adaptation = *mode;
    c.simulator.shiftEvery = a.shiftEvery;
  }
  const auto textBackend = makeTextBackend(command, a.text);
  if (!textBackend) return false;
  c.textBackend = *textBackend;
  c.steps = a.steps;
  c.evalEvery = a.evalEvery;
  c.evalTasks = a.evalTasks;
  c.maxEvalEpisodeSteps = a.maxEvalSteps;
  c.task = a.task;
  c.periodicResetEvery = a.periodicEvery;
  c.simulator.unsatisfiableStockProbability = a.unsatisfiable;
  c.simulator.participant = a.participant;
  // The solver's budgets are the domain's unless given: set once the program is loaded (solverOptionsFor).
  c.approach.epsilon = a.epsilon;
  c.approach.replan = a.replan;
  return true;
}

// A factory for the program's simulator, or nullopt after printing which domains exist. An external simulator is
// started once here, so that a program it does not fit is refused before any trial (every mismatch listed: a
// sim::ExternalSimulatorError), and its warnings are printed once.
inline std::optional<approach::SimulatorFactory> domainSimulator(const std::string& command,
                                                                 const app::LoadedProgram& lp,
                                                                 const sim::SimulatorOptions& options,
                                                                 const ExternalSimulatorArgs& external) {
  const std::string& domain = lp.graph().domain;
  approach::SimulatorFactory factory = simulatorFactory(lp, external);
  if (const auto probe = factory(options, 0)) {
    if (const auto* ext = dynamic_cast<const sim::ExternalSimulator*>(probe.get()))
      for (const auto& w : ext->manifestWarnings()) fmt::print(stderr, "cbtl {}: warning: {}\n", command, w);
    return factory;
  }
  fmt::print(stderr, "cbtl {}: error: {}: no simulator for domain '{}' (built in:", command, lp.path(), domain);
  for (const auto& d : domains::knownDomains()) fmt::print(stderr, " {}", d);
  fmt::print(stderr, "); give one with --simulator CMD or a `simulator \"CMD\";` line (docs/simulator-protocol.md)\n");
  return std::nullopt;
}

}  // namespace cbtl::cli
