// `cbtl run FILE --approach A --seed S --steps N --eval-every K --eval-tasks M --out DIR`: one trial of the
// paper's experiment in the domain's simulator. Exit codes: 0 ok, 1 bad input, 2 usage, 70 internal error.
#include "CommandRegistry.h"
#include "RuntimeSupport.h"

#include "UserModel.h"

#include <fmt/core.h>

#include <chrono>
#include <exception>
#include <string>

namespace {

struct RunArgs {
  std::string file, approach = "cbtl", out, task, nonstationary = "none", profile, stdlibDir;
  std::uint64_t seed = 0;
  std::int64_t steps = 10000, evalEvery = 100, maxEvalSteps = 100, shiftEvery = 3000, periodicEvery = 1000;
  int evalTasks = 10;
  double epsilon = 0.5, unsatisfiable = 0;
  bool replan = false, quiet = false;
  cbtl::solver::SolverOptions solver;
  cbtl::cli::TextBackendArgs text;
};

int runTrial(const RunArgs& a) {
  using namespace cbtl;
  const auto kind = approach::parseApproach(a.approach);
  if (!kind) {
    fmt::print(stderr, "cbtl run: error: unknown approach '{}' (choose one of: cbtl, no-personalization, free-explore, "
                       "exploit-only, epsilon-greedy)\n", a.approach);
    return 2;
  }
  approach::ExperimentConfig c;
  if (a.nonstationary != "none") {
    const auto mode = approach::parseAdaptation(a.nonstationary);
    if (!mode) {
      fmt::print(stderr, "cbtl run: error: unknown --nonstationary mode '{}' (none, no-adapt, user-reset, periodic-reset)\n",
                 a.nonstationary);
      return 2;
    }
    c.nonstationary = true;
    c.adaptation = *mode;
    c.simulator.shiftEvery = a.shiftEvery;
  }
  const auto textBackend = cli::makeTextBackend("run", a.text);
  if (!textBackend) return 2;
  c.textBackend = *textBackend;
  auto lp = cli::loadForRun("run", a.file, a.stdlibDir);
  if (!lp) return 1;
  c.approach.kind = *kind;
  c.approach.epsilon = a.epsilon;
  c.approach.replan = a.replan;
  c.seed = a.seed;
  c.steps = a.steps;
  c.evalEvery = a.evalEvery;
  c.evalTasks = a.evalTasks;
  c.maxEvalEpisodeSteps = a.maxEvalSteps;
  c.task = a.task;
  c.outDir = a.out;
  c.progress = !a.quiet;
  c.periodicResetEvery = a.periodicEvery;
  c.simulator.unsatisfiableStockProbability = a.unsatisfiable;
  c.solverOptions = a.solver;
  c.initialProfile = a.profile;
  if (domains::createSimulator(lp->graph().domain, c.simulator, 0) == nullptr) {
    fmt::print(stderr, "cbtl run: error: {}: no simulator for domain '{}' (known:", a.file, lp->graph().domain);
    for (const auto& d : domains::knownDomains()) fmt::print(stderr, " {}", d);
    fmt::print(stderr, ")\n");
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  const approach::ExperimentResult r = approach::runExperiment(*lp, cli::simulatorFactory(lp->graph().domain), c);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!a.quiet) {
    fmt::print("{} on {} (seed {}): {} steps, {} tasks completed in training, {} solves ({} failed, {} replanned)\n",
               a.approach, lp->graph().domain, a.seed, a.steps, r.mealsServed, r.trainSolves, r.trainSolveFailures, r.trainReplans);
    fmt::print("eval satisfaction: first {:+.2f}, last {:+.2f}, mean over {} checkpoints {:+.3f}\n",
               r.evals.empty() ? 0.0 : r.evals.front().mean, r.evals.empty() ? 0.0 : r.evals.back().mean, r.evals.size(),
               r.meanEval());
    fmt::print("{:.2f} s wall clock; {} training solver iterations\n", seconds, r.solverIterations);
    if (r.textModelErrors > 0) {
      fmt::print("{} text-model updates failed (the old theta was kept); the first: {}\n", r.textModelErrors,
                 r.firstTextModelError);
    }
    if (!a.out.empty()) fmt::print("wrote {}/train.csv, eval.csv, config.json, profile.json, models/\n", a.out);
  }
  return 0;
}

void addRun(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "train and evaluate one approach on a domain (the paper's experiment loop)");
  cmd->add_option("file", args->file, "the domain's .cbtl file")->required();
  cmd->add_option("--approach", args->approach, "cbtl | no-personalization | free-explore | exploit-only | epsilon-greedy")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "run seed (same seed, same results)")->capture_default_str();
  cmd->add_option("--steps", args->steps, "training steps")->capture_default_str();
  cmd->add_option("--eval-every", args->evalEvery, "evaluate every K steps")->capture_default_str();
  cmd->add_option("--eval-tasks", args->evalTasks, "held-out tasks per evaluation")->capture_default_str();
  cmd->add_option("--max-eval-steps", args->maxEvalSteps, "step limit of one evaluation episode")->capture_default_str();
  cmd->add_option("--out", args->out, "write train.csv, eval.csv, models and the profile here");
  cmd->add_option("--task", args->task, "task to run (default: the first)");
  cmd->add_flag("--replan", args->replan, "when the full CSP is unsatisfiable, replan without personalized constraints");
  cmd->add_option("--epsilon", args->epsilon, "epsilon-greedy's exploration probability")->capture_default_str();
  cmd->add_option("--nonstationary", args->nonstationary,
                  "shift the user's preferences: none | no-adapt | user-reset | periodic-reset")->capture_default_str();
  cmd->add_option("--shift-every", args->shiftEvery, "steps between preference shifts")->capture_default_str();
  cmd->add_option("--periodic-reset-every", args->periodicEvery, "steps between model resets (periodic-reset)")->capture_default_str();
  cmd->add_option("--unsatisfiable-stock", args->unsatisfiable,
                  "probability that a restock cannot satisfy the user (Cooking)")->capture_default_str();
  cmd->add_option("--profile", args->profile, "start from this user profile");
  cmd->add_option("--stdlib", args->stdlibDir, "standard library folder (default: embedded)");
  cmd->add_flag("--quiet,-q", args->quiet, "no progress bar or summary");
  cbtl::cli::addSolverOptions(cmd, args->solver);
  cbtl::cli::addTextBackendOptions(cmd, args->text);
  cmd->callback([args, &exitCode]() {
    try {
      exitCode = runTrial(*args);
    } catch (const cbtl::model::ProfileError& e) {
      fmt::print(stderr, "cbtl run: error: {}\n", e.what());
      exitCode = 1;
    } catch (const cbtl::rt::RuntimeError& e) {
      fmt::print(stderr, "cbtl run: error: {}\n", e.what());
      exitCode = 1;
    } catch (const std::exception& e) {
      fmt::print(stderr, "cbtl run: error: {}\n", e.what());
      exitCode = 1;
    }
  });
}

const cbtl::cli::RegisterCommand registerRun(10, addRun);

}  // namespace
