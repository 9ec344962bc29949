// ReplSession.h — the state behind `cbtl repl`: one loaded program, the world it is solved against, the user
// model being learned, and the loop a person drives by hand (solve, explain, act, give feedback, learn, undo).
//
// A session owns, for the program loaded last:
//   - the observation every solve reads: the domain simulator's (when the program's domain has one; its world is
//     made with the session's seed) or zeros, with the values set by `observe NAME = VALUE` written over it;
//   - the user model (the prior, or a profile loaded from JSON) and a snapshot of it before every `learn`, so
//     `undo` restores exactly the model before the last one (robot features are read in the world of that moment
//     and are not recomputed);
//   - the last plan (its CSP points into the program and the user model: any load, learn, undo or reset drops it);
//   - the feedback events queued since the last `learn`, each checked against its `feedback` declaration.
// The solver keeps its random stream and its memory of satisfying values across solves, as a run's does; `reset`
// reseeds it with the session's seed.
//
// Every command prints to `out`; an error prints "error: ..." there too (a transcript keeps the order) and makes
// execute() return Outcome::Failed. Nothing a person types ends the session but quit or the end of the input.
#pragma once

#include "app/LoadedProgram.h"
#include "app/profile/ProfileStore.h"
#include "runtime/approach/Approach.h"
#include "runtime/approach/Learner.h"
#include "runtime/approach/Planner.h"
#include "runtime/model/UserModel.h"
#include "runtime/sim/DomainSimulator.h"
#include "runtime/solver/Solver.h"

#include <atomic>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::app::repl {

struct ReplConfig {
  std::string stdlibDir;                                     // empty: the embedded standard library
  std::shared_ptr<const textpref::TextBackend> textBackend;  // null: the offline descriptor model
  std::uint64_t seed = 0;                                    // the world's and the solver's
  // Solver options for a program of a domain (the command line's over the domain's budgets).
  std::function<solver::SolverOptions(const std::string& domain)> solverOptions;
  // Set while a solve runs: it stops with Interrupted (the caller's SIGINT handler sets it; execute() clears it).
  std::atomic<bool>* interrupt = nullptr;
  // A profile store (null: none): the loaded program's model starts from `user`'s stored profile for its domain,
  // and every learn, undo, profile load and reset stores a new version (with the learned events' provenance).
  std::shared_ptr<profile::ProfileStore> store;
  std::string user;
  // An external simulator (app/SimulatorSource.h): this command instead of the program's `simulator` line or its
  // in-process domain; every answer awaited at most simulatorTimeoutMs.
  std::string simulatorCommand;
  int simulatorTimeoutMs = 30000;
};

class ReplSession {
 public:
  enum class Outcome { Ok, Failed, Quit };

  ReplSession(ReplConfig config, std::FILE* out);
  ~ReplSession();

  // Runs one command (a whole input, continuation lines already joined).
  Outcome execute(const std::string& input);

  // Whether `text` is an unfinished input: an open bracket or quote, or a line ending in '\'.
  static bool needsMoreInput(const std::string& text);

  // Candidates for completing the word that ends `line` (the text before the cursor): command names first,
  // then the names the command takes (tasks, variables, observations, feedback events, members, files).
  std::vector<std::string> completions(const std::string& line) const;
  // What completes after `NAME =`: the values of NAME's type (nullopt: no variable or observation of that name).
  std::optional<std::vector<std::string>> valuesOf(const std::string& name) const;

  bool loaded() const { return lp_ != nullptr; }
  const LoadedProgram* program() const { return lp_.get(); }

  // The commands, for help and completion: name, argument synopsis, one line of description.
  struct CommandInfo {
    std::string name, synopsis, summary;
  };
  static const std::vector<CommandInfo>& commands();

 private:
  struct LearnedBatch {
    std::vector<sim::FeedbackEvent> events;
    std::string modelBefore;   // the user model's JSON before the batch
    std::string what;          // "learn of 3 events", "profile load of p.json"
    std::int64_t version = 0;  // the store's version it made (0: no store)
  };
  struct PendingEvent {
    sim::FeedbackEvent event;
    std::string source;  // "typed" or "simulated user"
  };

  bool load(const std::string& path);
  // The profile store's part (ReplProfileStore.cpp). The head of the user's profile for the program's domain, read
  // into the fresh model (none yet: the prior); throws model::ProfileError when it does not fit the program.
  void loadStoredProfile();
  // Stores the current model as a new version and returns its number (0 without a store). Throws
  // profile::StoreError, after which the caller puts the model back; so it does when another process stored a
  // version of this profile since the session read or wrote its own (storing would drop that learning).
  std::int64_t storeModel(const std::vector<PendingEvent>& events, const std::string& reason);
  // " (stored as version N)", or "" for 0.
  static std::string storedNote(std::int64_t version);
  void dropProgram();
  bool requireProgram();
  bool fail(const std::string& message);
  void resetWorld(std::uint64_t seed);
  void makeSolver();
  approach::StepWorld stepWorld() const;

  // One method per command; `args` is the text after the command's name, trimmed.
  bool cmdHelp(const std::string& args);
  bool cmdLoad(const std::string& args);
  bool cmdReload(const std::string& args);
  bool cmdList(const std::string& args);
  bool cmdShow(const std::string& args);
  bool cmdObserve(const std::string& args);
  bool observeFile(const std::string& path);
  bool cmdSolve(const std::string& args);
  bool cmdExplain(const std::string& args);
  bool cmdWhyNot(const std::string& args);
  bool cmdAct(const std::string& args);
  bool cmdFeedback(const std::string& args);
  bool cmdLearn(const std::string& args);
  bool cmdProfile(const std::string& args);
  bool cmdUndo(const std::string& args);
  bool cmdReset(const std::string& args);
  bool cmdEval(const std::string& expr);  // ReplEval.cpp

  void listVariables() const;
  void listConstraints() const;
  void listPersonal() const;
  void listTasks() const;
  void listSkills() const;
  void listObservations() const;
  void listEvents() const;
  void showPending() const;
  // The names of `kind` ("task", "variable", "observation", "event", "command", "list", ...), for completion.
  std::vector<std::string> namesOf(const std::string& kind) const;

  ReplConfig config_;
  std::FILE* out_;
  std::string path_;
  std::unique_ptr<LoadedProgram> lp_;
  std::unique_ptr<sim::DomainSimulator> world_;
  std::uint64_t worldSeed_ = 0;
  std::unique_ptr<model::UserModel> user_;
  std::int64_t storedVersion_ = 0;  // the store's version the model was read from or last stored as (0: none)
  std::unique_ptr<solver::Solver> solver_;
  std::vector<double> observation_;
  std::map<std::string, std::string> typedObservations_;  // set by hand since the world last said, as typed
  std::unique_ptr<approach::Plan> plan_;
  std::vector<double> planObservation_;
  bool planActed_ = false;
  std::vector<PendingEvent> pending_;
  std::vector<LearnedBatch> learned_;
};

}  // namespace cbtl::app::repl
