// Checkpoint.h — what `--resume` needs to continue a run exactly, and the run's output files (RunOutput).
//
// A checkpoint is taken at every evaluation point (every evalEvery steps, and at the end), after that point's
// eval.csv row and models/<step>.json are written. Its order makes every prefix of it safe to be killed in:
//   1. train.csv, eval.csv, world-calls.jsonl and motions.jsonl.gz (when there is one) are flushed and fsynced;
//   2. checkpoint.json is replaced atomically. It holds the step, the three files' byte lengths at that
//      moment, the training solver's state (RNG and memory, Solver::saveState; every evaluation starts its
//      own solver afresh, Experiment.h), the approach RNG, the program's
//      interned texts, the profile learned so far, the pending calls of the current plan and their cursor,
//      and the ExperimentResult so far.
// `--resume` truncates those files to the recorded lengths (dropping rows of steps after the checkpoint),
// restores that state, and rebuilds the training world by replaying the logged calls into a fresh simulator
// from the same seed — no CSP of a step before the checkpoint is solved again. A replayed call whose result
// differs from the logged one (a simulator that is not deterministic from its seed) stops the resume with an
// error. The evaluation world needs no replay: every evaluation episode starts with reset(seed), and an
// evaluation twin never changes the training world (DomainSimulator.h).
//
// The resumed run writes the same bytes into train.csv, eval.csv, models/*.json and profile.json as an
// uninterrupted run with the same options (tests/unit/runtime/ResumeTest.cpp).
#pragma once

#include "runtime/approach/Experiment.h"
#include "runtime/approach/Learner.h"
#include "runtime/approach/RunDirectory.h"
#include "runtime/sim/DomainSimulator.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::approach {

nlohmann::json toJson(const sim::ActionCall& call);
sim::ActionCall actionCallFromJson(const nlohmann::json& j);
nlohmann::json toJson(const ExperimentResult& result);
ExperimentResult experimentResultFromJson(const nlohmann::json& j);

// The keys (dotted for nested objects, e.g. "solver.max_iters") whose values differ between two configs,
// with both values: "steps (this command: 500, the run: 1000)".
std::vector<std::string> differingKeys(const nlohmann::json& now, const nlohmann::json& saved);

struct Checkpoint {
  std::int64_t step = 0;
  std::uint64_t trainCsvBytes = 0, evalCsvBytes = 0, worldLogBytes = 0, worldCalls = 0, motionsBytes = 0;
  nlohmann::json trainSolver, profile;
  std::string approachRng;
  std::vector<std::string> strings;  // the program's interned texts, in id order
  std::vector<sim::ActionCall> pending;
  std::size_t next = 0;
  StepWorld planWorld;  // the solution and observation the pending calls come from (what feedback is about)
  bool planOpen = false, planDryRun = false;  // the pending plan's execution is not yet counted; it was dry-run
  ExperimentResult result;

  nlohmann::json toJson() const;
  // Throws RunDirectoryError naming `source` when the document is not a checkpoint.
  static Checkpoint fromJson(const nlohmann::json& j, const std::string& source);
};

// The training world, with a log of every call that changes it (reset, act, idle) as JSON lines, each with a
// digest of its result. observe(), worldState() and requestedTask() are const and pass through.
class RecordingSimulator final : public sim::DomainSimulator {
 public:
  explicit RecordingSimulator(std::unique_ptr<sim::DomainSimulator> inner) : inner_(std::move(inner)) {}

  void reset(std::uint64_t seed) override;
  sim::Observation observe() const override { return inner_->observe(); }
  sim::StepResult act(const sim::ActionCall& call) override;
  sim::StepResult idle() override;
  const world::WorldState* worldState() const override { return inner_->worldState(); }
  std::string requestedTask() const override { return inner_->requestedTask(); }
  std::vector<std::string> judgedPreferences() const override { return inner_->judgedPreferences(); }
  std::unique_ptr<sim::DomainSimulator> makeEvaluationTwin() const override { return inner_->makeEvaluationTwin(); }

  // Lines logged since the last call (each ends in '\n'), and the number of calls logged so far.
  std::string takeLog();
  std::uint64_t calls() const { return calls_; }
  // Applies logged lines (world-calls.jsonl) to the inner world without logging them again. Throws
  // RunDirectoryError naming `source` and the line when a line is malformed or its result differs.
  void replay(const std::string& lines, const std::string& source);

 private:
  void log(nlohmann::json entry, const sim::StepResult& r);

  std::unique_ptr<sim::DomainSimulator> inner_;
  std::string log_;
  std::uint64_t calls_ = 0;
};

// A run's output folder (RunDirectory.h lists its files). Without a folder (dir empty) every call does nothing.
class RunOutput {
 public:
  // Locks `dir` and applies `mode`: Fresh refuses a folder that holds a run; Force removes the run's files;
  // Resume compares `config` with config.json (refusing differences, naming the keys) and reads complete.json
  // or checkpoint.json (with neither, the run starts afresh). A run that starts afresh writes config.json and
  // the two CSV headers. Throws RunDirectoryError.
  RunOutput(const std::string& dir, RunMode mode, const nlohmann::json& config, const std::string& trainHeader,
            const std::string& evalHeader);

  bool enabled() const { return !dir_.empty(); }
  const std::string& dir() const { return dir_; }
  // Resume of a complete run: its result (nothing is rerun).
  const std::optional<ExperimentResult>& completed() const { return completed_; }
  // Resume of a complete run: the wall-clock seconds its timing.json recorded (none for an earlier cbtl's run).
  std::optional<double> recordedSeconds() const { return recordedSeconds_; }
  // Resume of an interrupted run: its last complete checkpoint.
  const std::optional<Checkpoint>& resumeFrom() const { return checkpoint_; }
  // The logged training-world calls up to the checkpoint (for RecordingSimulator::replay).
  std::string worldLog() const;
  std::string worldLogPath() const;

  void trainRow(const std::string& row) { train_.append(row); }
  // One line of motions.jsonl.gz (with its newline). Lines are kept until the next checkpoint (or the end), then
  // appended as one gzip member (GzipMember.h); the file is created by the first member.
  void motionLine(const std::string& line);
  void evalRow(const std::string& row) { eval_.append(row); }
  void writeModel(std::int64_t step, const std::string& profileJson);
  // Completes `cp` with the files' lengths, makes the files durable, then replaces checkpoint.json.
  void checkpoint(Checkpoint& cp, const std::string& worldLines);
  // Writes profile.json, then the marker complete.json (last), then drops the resume state.
  void finish(const std::string& profileJson, const ExperimentResult& result);

  std::function<void(const char*, std::int64_t)> hook;

 private:
  std::string path(const std::string& name) const;
  void startFresh(const nlohmann::json& config, const std::string& trainHeader, const std::string& evalHeader);
  void openForResume(const nlohmann::json& config);

  std::string dir_;
  std::unique_ptr<DirectoryLock> lock_;
  void flushMotions();
  AppendFile train_, eval_, world_, motions_;
  std::string motionText_;  // lines not yet compressed
  std::optional<ExperimentResult> completed_;
  std::optional<Checkpoint> checkpoint_;
  // Wall clock: this process's part starts at construction; the parts before it (a resumed run) are carried in
  // checkpoint.json's "elapsed_seconds" (not part of the Checkpoint: it differs between identical runs).
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  double priorSeconds_ = 0;
  std::optional<double> recordedSeconds_;
  double elapsedSeconds() const;
};

}  // namespace cbtl::approach
