// cbtl feedback — one step of the learning loop from the command line: feedback events, typed as a person would
// give them in the REPL, checked against their declarations, learned into a profile and saved.
//
//   cbtl feedback domains/cooking/cooking.cbtl --profile alice.json
//       --event 'mealCritique(seasoning, salt, 3, 31, 0.9, wantHotter, wantMore)' [--solution sol.json]
//
// Every event is checked before anything is learned: one bad event changes nothing. A profile file that does not
// exist yet is created from the prior. The world the events' features are read in (an occlusion score, say) is the
// solution's (--solution, from `cbtl solve --format json`) or else the domain simulator's with --seed, with
// --observe values written over it.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "app/ObservationFile.h"
#include "app/PlanReport.h"
#include "app/SolutionFile.h"
#include "app/profile/ProfileStore.h"
#include "app/repl/ValueSyntax.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {

struct FeedbackArgs {
  std::string file, profile, profileDb, user, solution, observe, stdlibDir;
  std::vector<std::string> events;
  std::uint64_t seed = 0;
  cbtl::cli::TextBackendArgs text;
  cbtl::cli::ExternalSimulatorArgs external;
};

// The moment the events are about: the solution's when given, else the simulator's world (or zeros).
cbtl::approach::StepWorld momentOf(const FeedbackArgs& a, cbtl::app::LoadedProgram& lp) {
  using namespace cbtl;
  approach::StepWorld moment;
  sim::Observation observed;
  if (!a.solution.empty()) {
    app::SolutionMoment s = app::readSolutionFile(a.solution, lp.program());
    moment.assignment = std::move(s.assignment);
    moment.observation = std::move(s.observation);
  } else if (auto world = cli::simulatorFactory(lp, a.external)({}, a.seed)) {
    lp.syncWorld(*world);
    observed = world->observe();
  }
  if (!a.observe.empty()) {
    if (!a.solution.empty()) {
      observed = app::readObservationEntries(a.observe, lp.program());
    } else {
      observed = app::readObservationFile(a.observe, lp.program(), std::move(observed));
    }
  }
  if (moment.observation.empty()) moment.observation.assign(lp.program().observationWidth(), 0.0);
  for (const auto& [name, value] : observed) {
    const auto& slot = lp.program().observationSlots().at(name);
    std::string error;
    if (!approach::fromSimValue(lp.program(), slot.type, value, moment.observation.data() + slot.offset, error))
      throw std::runtime_error(fmt::format("observation {}: {}", name, error));
  }
  return moment;
}

int runFeedback(const FeedbackArgs& a) {
  using namespace cbtl;
  const auto textBackend = cli::makeTextBackend("feedback", a.text);
  if (!textBackend) return 2;
  auto lp = cli::loadForRun("feedback", a.file, a.stdlibDir);
  if (!lp) return 1;
  std::vector<sim::FeedbackEvent> events;
  for (const auto& text : a.events) {
    std::string error;
    std::optional<sim::FeedbackEvent> e = app::repl::checkedEvent(lp->program(), text, error);
    if (!e) {
      fmt::print(stderr, "cbtl feedback: error: --event: {}\n", error);
      return 1;
    }
    events.push_back(std::move(*e));
  }
  std::string solutionText;
  if (!a.solution.empty()) solutionText = app::readSolutionFile(a.solution, lp->program()).text;
  const approach::StepWorld moment = momentOf(a, *lp);
  const std::string& domain = lp->graph().domain;
  std::optional<model::UserModel> user;
  approach::LearnReport report;
  bool exists = false;
  std::size_t before = 0;
  // Learns the events into `user` as loaded (or the prior).
  const auto learn = [&] {
    before = user->dataCount();
    report = lp->learner().learn(events, *user, moment);
  };
  std::string where = a.profile;
  if (!a.profileDb.empty()) {
    app::profile::ProfileStore store(a.profileDb);
    std::vector<app::profile::NewEvent> stored;
    for (const auto& e : events)
      stored.push_back({app::profile::EventSource::Command, app::renderEvent(e), solutionText});
    // The head is read, learned from and the result stored in one write transaction: a concurrent `cbtl feedback`
    // on the same profile waits and then learns from this one's version, so no learning is lost.
    const std::int64_t version = store.learnOnHead(a.user, domain, [&](const auto& head) {
      user.emplace(lp->graph(), *textBackend);
      exists = head.has_value();
      if (head)
        user->fromJson(head->model,
                       fmt::format("{} ({}'s {} profile, version {})", a.profileDb, a.user, domain, head->version));
      learn();
      return app::profile::LearningStep{stored, user->toJson(), static_cast<std::int64_t>(user->dataCount()), "learn"};
    });
    where = fmt::format("{}'s {} profile (version {} in {})", a.user, domain, version, a.profileDb);
  } else {
    user.emplace(lp->graph(), *textBackend);
    exists = std::filesystem::exists(a.profile);
    if (exists) user->load(a.profile);
    learn();
    user->save(a.profile);
  }
  for (const auto& p : report.problems) fmt::print("warning: not learned: {}\n", p);
  for (const auto& m : report.modelErrors) fmt::print("warning: {}\n", m);
  for (const auto& e : events) fmt::print("event: {}\n", app::renderEvent(e));
  fmt::print("learned {} label{} from {} event{}; {} {} holds {} labels (was {})\n", report.labels,
             report.labels == 1 ? "" : "s", events.size(), events.size() == 1 ? "" : "s",
             exists ? "the profile" : "the new profile", where, user->dataCount(), before);
  if (*textBackend) cli::printLlmFaults(stdout, (*textBackend)->faultReport());
  return 0;
}

void addFeedback(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<FeedbackArgs>();
  CLI::App* cmd = app.add_subcommand(
      "feedback", "learn feedback events, typed as in the REPL (name(args...)), into a user profile and save it");
  cmd->add_option("file", args->file, "the domain's .cbtl file, or its graph from `cbtlc emit --format json`")
      ->required();
  CLI::Option* file =
      cmd->add_option("--profile", args->profile, "the profile JSON to update (created from the prior when missing)");
  CLI::Option* db = cmd->add_option("--profile-db", args->profileDb,
                                    "or the profile store (SQLite) to update: a new version of --user's profile");
  CLI::Option* user = cmd->add_option("--user", args->user, "whose profile, in --profile-db");
  file->excludes(db);
  db->needs(user);
  user->needs(db);
  cmd->add_option("--event", args->events, "a feedback event, e.g. 'dipAnswer(frenchFries, ketchup, bbqSauce)'")
      ->required();
  cmd->add_option("--solution", args->solution,
                  "the solution the events are about (cbtl solve --format json): its assignment and observation");
  cmd->add_option("--observe", args->observe, "a JSON file of observations by name, written over the world's");
  cmd->add_option("--seed", args->seed, "seed of the domain simulator's world (without --solution)")
      ->capture_default_str()
      ->check(cbtl::cli::unsignedIn(0));
  cmd->add_option("--stdlib", args->stdlibDir,
                  "standard library folder (default: embedded; not used by an emitted graph)");
  cbtl::cli::addTextBackendOptions(cmd, args->text);
  cbtl::cli::addExternalSimulatorOptions(cmd, args->external);
  cmd->callback([args, &exitCode]() {
    if (args->profile.empty() && args->profileDb.empty())
      throw CLI::RequiredError("--profile or --profile-db (where the learned profile goes)");
    cbtl::cli::runCommand("feedback", exitCode, [&] { return runFeedback(*args); });
  });
}

const cbtl::cli::RegisterCommand registerFeedback(21, addFeedback);

}  // namespace
