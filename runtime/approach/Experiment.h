// Experiment.h — the paper's experiment loop (the reference's, fixed where the reference was wrong).
//
// Train for `steps` steps in one world that is never reset (a served meal restocks it); every `evalEvery`
// steps (and at step 0 and at the end), copy what was learned into an evaluation agent and run `evalTasks`
// episodes, episode i in a world reset with evaluationTaskSeed(seed, i) — the same held-out tasks at every
// checkpoint (the reference's evaluation tasks drifted between checkpoints), each checkpoint's evaluation solved
// by a solver started afresh from evaluationSolverSeed(seed) (so a checkpoint's numbers do not depend on how many
// evaluations came before it), and different tasks for
// different run seeds (the reference's seed + 100000 + i made seeds s and s + 1 share nine of ten tasks,
// so ten seeds were far from ten independent samples). An episode scores the sum of
// the user's satisfaction over at most `maxEvalEpisodeSteps` steps; an episode whose CSP cannot be solved
// scores 0 and counts as a failed task.
//
// Outputs (when `outDir` is set): train.csv, eval.csv (the reference's columns plus task-success and
// preferences-met rates, and one met rate per preference the domain judges, sim::DomainSimulator::
// judgedPreferences), config.json (with the text backend, server and model), models/<step>.json at every
// checkpoint and, at the end, profile.json, llm.json (the text backend and its failure counts, RunReport.h) and
// then the completion marker complete.json. A folder that already holds a run is refused, replaced or resumed
// as `runMode` says; every evaluation point is a checkpoint that `--resume` continues from exactly
// (RunDirectory.h lists the files and their guarantees, Checkpoint.h what a checkpoint holds).
#pragma once

#include "runtime/approach/Approach.h"
#include "runtime/approach/PreparedProgram.h"
#include "runtime/approach/RunDirectory.h"
#include "runtime/sim/DomainSimulator.h"
#include "runtime/solver/Solver.h"

#include "runtime/textpref/FaultStats.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::textpref {
class TextBackend;
}

namespace cbtl::approach {

// The paper's nonstationary variants (Figure 5): keep everything learned, reset when the user announces a
// change, or reset every `periodicResetEvery` steps.
enum class Adaptation { NoAdapt, UserReset, PeriodicReset };
const char* toString(Adaptation a);
std::optional<Adaptation> parseAdaptation(const std::string& name);

struct ExperimentConfig {
  ApproachConfig approach;
  std::uint64_t seed = 0;
  std::int64_t steps = 10000;
  std::int64_t evalEvery = 100;
  int evalTasks = 10;
  std::int64_t maxEvalEpisodeSteps = 100;
  double dt = 0.01;  // execution time per step, for the CSV's time column
  std::string task;  // empty: the program's first task
  std::string outDir;
  bool progress = false;
  bool nonstationary = false;
  Adaptation adaptation = Adaptation::NoAdapt;
  std::int64_t periodicResetEvery = 1000;
  sim::SimulatorOptions simulator;
  solver::SolverOptions solverOptions;
  std::string initialProfile;  // a profile to start from (optional)
  // Or the profile's JSON itself (a profile store's version), named by `initialProfile` in config.json.
  std::string initialProfileJson;
  // Keep every training step's learned feedback events in ExperimentResult::feedback (for a profile store's
  // provenance). Only this process's steps: a resumed run keeps those after its checkpoint.
  bool recordFeedback = false;
  // Writes what the robot did (StepResult::motions) to the run folder's motions.jsonl (RunDirectory.h).
  bool recordMotions = true;
  // Makes the models of text factors (`model text(...)`); null: the offline descriptor model (no network).
  std::shared_ptr<const textpref::TextBackend> textBackend;
  RunMode runMode = RunMode::Fresh;  // what to do when outDir already holds a run
  // Test-only: called as testHook(point, step) at "step" (training step `step` done, its row not yet flushed),
  // "model" (models/<step>.json written), "checkpoint" (the files of checkpoint `step` durable, checkpoint.json
  // not yet replaced) and "finish" (profile.json written, complete.json not yet). It may throw or kill the process.
  std::function<void(const char* point, std::int64_t step)> testHook;
};

// How competently the robot acted: requests solved within the solver's budget, solved plans that ran to their end
// (or to the end of their task) without a failed action, and plans the dry run had accepted that then failed
// (the world model and the simulator disagree: a bug, counted apart so it can be driven to 0).
struct Competence {
  std::int64_t requests = 0, solved = 0;
  std::int64_t executed = 0, failed = 0;  // solved plans, by how their execution ended
  std::int64_t dryRunMismatches = 0;      // failed plans that had been dry-run
  std::int64_t caregiverResets = 0;       // times a person had to put a stuck robot back (StepResult)
  double solvedRate() const { return requests > 0 ? static_cast<double>(solved) / requests : 1.0; }
  double executedRate() const {
    return executed + failed > 0 ? static_cast<double>(executed) / static_cast<double>(executed + failed) : 1.0;
  }
  void add(const Competence& o);
};

// How often one of the user's preferences (sim::StepResult::preferences) was met in a checkpoint's episodes.
struct PreferenceTally {
  int met = 0, judged = 0;
  double rate() const { return judged > 0 ? static_cast<double>(met) / judged : 0.0; }
};

// The values one measure of a task (sim::StepResult::measures) took in a checkpoint's episodes.
struct MeasureTally {
  double min = 0, sum = 0;
  int count = 0;
  void add(double v) {
    min = count == 0 ? v : std::min(min, v);
    sum += v;
    ++count;
  }
  double mean() const { return count > 0 ? sum / count : 0.0; }
};

struct EvalPoint {
  std::int64_t step = 0;
  std::vector<double> satisfaction;  // per episode
  double mean = 0;
  double taskSuccessRate = 0;                          // episodes that completed their task
  double preferencesMetRate = 0;                       // episodes whose user was satisfied
  int replans = 0;                                     // episodes that had to drop the personalized constraints
  Competence competence;                               // over this checkpoint's episodes
  std::map<std::string, PreferenceTally> preferences;  // by name, over this checkpoint's episodes
  std::map<std::string, MeasureTally> measures;        // by name, over this checkpoint's episodes
};

// The feedback events training step `step` learned from.
struct StepFeedback {
  std::int64_t step = 0;
  std::vector<sim::FeedbackEvent> events;
};

struct ExperimentResult {
  std::vector<EvalPoint> evals;
  std::string finalProfile;            // the learned model at the end (UserModel::toJson)
  std::size_t finalLabels = 0;         // its labelled examples (UserModel::dataCount)
  std::vector<StepFeedback> feedback;  // when ExperimentConfig::recordFeedback
  std::int64_t mealsServed = 0;        // tasks completed in training
  double trainSatisfaction = 0;        // sum over training
  std::int64_t trainSolves = 0, trainSolveFailures = 0, trainReplans = 0;
  Competence train, eval;  // eval: over every checkpoint
  std::uint64_t solverIterations = 0;
  // Learning steps whose text model kept its old theta (e.g. a language-model server failed), and the first one.
  std::int64_t textModelErrors = 0;
  std::string firstTextModelError;
  // Solutions re-checked before execution (training and evaluation) and those refused by the re-check
  // (Recheck.h: a runtime bug; never executed), with the first violation.
  std::int64_t rechecks = 0, recheckViolations = 0;
  std::string firstRecheckViolation;
  // The language model's failures in this run: ratings that fell back, by kind, and the circuit breaker.
  textpref::FaultReport llmFaults;
  // A complete run read back by --resume (nothing ran), with the wall-clock seconds it took when it ran (its
  // timing.json; not a result, never in complete.json), unset when an earlier cbtl did not record them.
  bool finishedEarlier = false;
  std::optional<double> recordedSeconds;
  double meanEval() const;
};

using SimulatorFactory =
    std::function<std::unique_ptr<sim::DomainSimulator>(const sim::SimulatorOptions&, std::uint64_t)>;

// Runs one trial. Throws rt::RuntimeError / model::ProfileError / std::runtime_error for bad input or a
// simulator that breaks the contract; never hangs (every loop is bounded by the configured budgets).
ExperimentResult runExperiment(const PreparedProgram& lp, const SimulatorFactory& factory,
                               const ExperimentConfig& config);

// The world seed of held-out evaluation task `task` of run `seed`.
std::uint64_t evaluationTaskSeed(std::uint64_t seed, int task);

// The seed every checkpoint's evaluation solver of run `seed` starts from.
std::uint64_t evaluationSolverSeed(std::uint64_t seed);

// Seeds for independent components derived from one run seed.
std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream);

}  // namespace cbtl::approach
