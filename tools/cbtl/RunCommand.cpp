// `cbtl run FILE --approach A --seed S --steps N --eval-every K --eval-tasks M --out DIR`: one trial of the
// paper's experiment in the domain's simulator. Exit codes: 0 ok, 1 bad input, 2 usage, 3 more requests failed than
// --max-failure-rate allows (app/RunFailures.h), 70 internal error.
// An --out folder that holds a run is refused unless --force (replace it) or --resume (continue it from its last
// checkpoint); approach/RunDirectory.h lists the files and their guarantees.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/Interrupt.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "app/PlanReport.h"
#include "app/profile/ProfileStore.h"
#include "runtime/approach/RunDirectory.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace {

struct RunArgs : cbtl::cli::TrialArgs {
  std::string approach = "cbtl", out, profile, profileDb, user;
  std::uint64_t seed = 0;
  bool quiet = false, force = false, resume = false;
};

// The run's final model as a new version of the user's profile, with every event it learned from (source
// "simulator", in the order of the training steps; the step numbers themselves are not stored).
// `learnedFrom` is the version the run started from (0: the prior); another process's version since then makes
// this a StoreError that writes nothing.
void storeRun(cbtl::app::profile::ProfileStore& store, const RunArgs& a, const cbtl::ir::ConstraintGraph& graph,
              const cbtl::approach::ExperimentResult& r, std::int64_t learnedFrom) {
  const std::string& domain = graph.domain;
  using namespace cbtl;
  std::vector<app::profile::NewEvent> events;
  for (const auto& step : r.feedback)
    for (const auto& e : step.events)
      events.push_back({app::profile::EventSource::Simulator, app::renderEvent(e, &graph), ""});
  const std::int64_t version =
      store.recordLearning(a.user, domain, events, r.finalProfile, static_cast<std::int64_t>(r.finalLabels),
                           fmt::format("run: {}, seed {}, {} steps", a.approach, a.seed, a.steps), learnedFrom);
  if (!a.quiet)
    fmt::print("stored the learned model as version {} of {}'s {} profile in {} ({} feedback events)\n", version,
               a.user, domain, a.profileDb, events.size());
}

int runTrial(const RunArgs& a) {
  using namespace cbtl;
  const auto kind = approach::parseApproach(a.approach);
  if (!kind) {
    fmt::print(stderr,
               "cbtl run: error: unknown approach '{}' (choose one of: cbtl, no-personalization, free-explore, "
               "exploit-only, epsilon-greedy)\n",
               a.approach);
    return 2;
  }
  approach::ExperimentConfig c;
  if (!cli::configureTrial("run", a, c)) return 2;
  auto lp = cli::loadForRun("run", a.file, a.stdlibDir);
  if (!lp) return 1;
  c.solverOptions = cli::solverOptionsFor(a.solver, lp->graph().domain);
  c.approach.kind = *kind;
  c.seed = a.seed;
  c.outDir = a.out;
  c.progress = !a.quiet;
  c.initialProfile = a.profile;
  std::optional<app::profile::ProfileStore> store;
  std::int64_t learnedFrom = 0;
  if (!a.profileDb.empty()) {
    store.emplace(a.profileDb);
    if (const auto head = store->head(a.user, lp->graph().domain)) {
      learnedFrom = head->version;
      c.initialProfile =
          fmt::format("{} ({}'s {} profile, version {})", a.profileDb, a.user, lp->graph().domain, head->version);
      c.initialProfileJson = head->model;
    }
    c.recordFeedback = true;
  }
  c.runMode = a.force ? approach::RunMode::Force : a.resume ? approach::RunMode::Resume : approach::RunMode::Fresh;
  c.testHook = approach::killHookFromEnvironment();
  const auto factory = cli::domainSimulator("run", *lp, c.simulator, a.external);
  if (!factory) return 1;
  cli::sayOnInterrupt(cli::interruptMessage("run", a.out, "the run up to its last checkpoint"));
  const auto start = std::chrono::steady_clock::now();
  const approach::ExperimentResult r = approach::runExperiment(*lp, *factory, c);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (store) storeRun(*store, a, lp->graph(), r, learnedFrom);
  if (!a.quiet) {
    fmt::print("{} on {} (seed {}): {} steps, {} tasks completed in training, {} solves ({} failed, {} replanned)\n",
               a.approach, lp->graph().domain, a.seed, a.steps, r.mealsServed, r.trainSolves, r.trainSolveFailures,
               r.trainReplans);
    fmt::print("eval satisfaction: first {:+.2f}, last {:+.2f}, mean over {} checkpoints {:+.3f}\n",
               r.evals.empty() ? 0.0 : r.evals.front().mean, r.evals.empty() ? 0.0 : r.evals.back().mean,
               r.evals.size(), r.meanEval());
    if (!r.evals.empty() && !r.evals.back().preferences.empty()) {
      fmt::print("preferences met at the last checkpoint:");
      for (const auto& [name, tally] : r.evals.back().preferences)
        fmt::print(" {} {}/{} ({:.2f})", name, tally.met, tally.judged, tally.rate());
      fmt::print("\n");
    }
    if (!r.evals.empty())
      for (const auto& [name, t] : r.evals.back().measures)
        fmt::print("{} at the last checkpoint: min {:.4g}, mean {:.4g} over {} tasks\n", name, t.min, t.mean(),
                   t.count);
    fmt::print("{:.2f} s wall clock; {} training solver iterations\n", seconds, r.solverIterations);
    fmt::print("{} solutions re-checked before execution, {} refused\n", r.rechecks, r.recheckViolations);
    cli::printCompetence(r.train, r.eval);
    if (r.textModelErrors > 0) {
      fmt::print("{} text-model updates failed (the old theta was kept); the first: {}\n", r.textModelErrors,
                 r.firstTextModelError);
    }
    cli::printLlmFaults(stdout, r.llmFaults);
    if (!a.out.empty())
      fmt::print(
          "wrote {}/train.csv, eval.csv, config.json, llm.json, profile.json, models/, timing.json, complete.json\n",
          a.out);
  } else {
    cli::printLlmFaults(stderr, r.llmFaults);
  }
  if (r.recheckViolations > 0) {
    // Never executed, but a solution the solver accepted broke a hard constraint: a runtime bug.
    fmt::print(stderr,
               "cbtl run: internal error: {} accepted solutions failed the independent re-check and were refused; the "
               "first: {}\n",
               r.recheckViolations, r.firstRecheckViolation);
    return 70;
  }
  const auto above = app::phasesAbove(
      {app::phaseFailures("training", r.train), app::evaluationFailures("evaluation", r.eval)}, a.maxFailureRate);
  if (!above.empty()) {
    fmt::print(stderr, "{}", app::failureWarning("run", a.file, above, a.maxFailureRate));
    return 3;
  }
  return 0;
}

void addRun(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd =
      app.add_subcommand("run", "train and evaluate one approach on a domain (the paper's experiment loop)");
  cbtl::cli::addTrialOptions(cmd, *args);
  cmd->add_option("--approach", args->approach,
                  "cbtl | no-personalization | free-explore | exploit-only | epsilon-greedy")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "run seed (same seed, same results)")
      ->capture_default_str()
      ->check(cbtl::cli::unsignedIn(0));
  cmd->add_option("--out", args->out, "write train.csv, eval.csv, models and the profile here");
  CLI::Option* file = cmd->add_option("--profile", args->profile, "start from this user profile");
  CLI::Option* db = cmd->add_option("--profile-db", args->profileDb,
                                    "start from --user's profile in this store and store the learned model as its "
                                    "next version, with the feedback events of the run");
  CLI::Option* user = cmd->add_option("--user", args->user, "whose profile, in --profile-db");
  file->excludes(db);
  db->needs(user);
  user->needs(db);
  auto* force = cmd->add_flag("--force", args->force, "replace the run already in --out (only the files a run writes)");
  cmd->add_flag("--resume", args->resume, "continue the run in --out from its last checkpoint (same options)")
      ->excludes(force);
  cmd->add_flag("--quiet,-q", args->quiet, "no progress bar or summary");
  cmd->callback([args, &exitCode]() { cbtl::cli::runCommand("run", exitCode, [&] { return runTrial(*args); }); });
}

const cbtl::cli::RegisterCommand registerRun(10, addRun);

}  // namespace
