#include "runtime/approach/Experiment.h"

#include "runtime/approach/Checkpoint.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/core/InternalError.h"

#include "runtime/textpref/RunReport.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace cbtl::approach {

namespace fs = std::filesystem;

const char* toString(Adaptation a) {
  switch (a) {
    case Adaptation::NoAdapt:
      return "no-adapt";
    case Adaptation::UserReset:
      return "user-reset";
    case Adaptation::PeriodicReset:
      return "periodic-reset";
  }
  return "?";
}

std::optional<Adaptation> parseAdaptation(const std::string& name) {
  for (auto a : {Adaptation::NoAdapt, Adaptation::UserReset, Adaptation::PeriodicReset}) {
    if (name == toString(a)) return a;
  }
  return std::nullopt;
}

void Competence::add(const Competence& o) {
  requests += o.requests;
  solved += o.solved;
  executed += o.executed;
  failed += o.failed;
  dryRunMismatches += o.dryRunMismatches;
  caregiverResets += o.caregiverResets;
}

double ExperimentResult::meanEval() const {
  if (evals.empty()) return 0;
  double s = 0;
  for (const auto& e : evals) s += e.mean;
  return s / static_cast<double>(evals.size());
}

std::uint64_t evaluationTaskSeed(std::uint64_t seed, int task) {
  return deriveSeed(seed + 100000, 1000 + static_cast<std::uint64_t>(task));
}

std::uint64_t evaluationSolverSeed(std::uint64_t seed) { return deriveSeed(seed + 100000, 1); }

std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream) {
  // SplitMix64 at the stream's position in the sequence started at `seed`: well-mixed, independent streams
  // from one run seed (stream 0 is splitMix64(seed)).
  return rt::splitMix64(seed + 0x9E3779B97F4A7C15ull * stream);
}

namespace {

void requireApplied(const sim::StepResult& r, const sim::ActionCall& call) {
  if (r.status == sim::ActionStatus::UnknownAction) {
    throw rt::InternalError(fmt::format("the simulator rejected action '{}': {}", call.name, r.message));
  }
}

// Executes calls from `next` until one consumes a step (calls that do not are part of that step).
sim::StepResult executeStep(sim::DomainSimulator& world, const std::vector<sim::ActionCall>& calls, std::size_t& next) {
  sim::StepResult merged;
  while (next < calls.size()) {
    const auto& call = calls[next++];
    sim::StepResult r = world.act(call);
    requireApplied(r, call);
    for (auto& f : r.feedback) merged.feedback.push_back(std::move(f));
    for (auto& p : r.preferences) merged.preferences.push_back(std::move(p));
    for (auto& v : r.measures) merged.measures.push_back(std::move(v));
    // Each motion is kept with the call that made it: `"call": ..., "motion": ...`, completed by the caller.
    for (auto& m : r.motions) merged.motions.push_back(fmt::format(R"("call":{},"motion":{})", toJson(call).dump(), m));
    if (r.hasSatisfaction) {
      merged.hasSatisfaction = true;
      merged.satisfaction += r.satisfaction;
    }
    merged.taskDone = merged.taskDone || r.taskDone;
    merged.taskFailed = merged.taskFailed || r.taskFailed;
    merged.preferencesChanged = merged.preferencesChanged || r.preferencesChanged;
    merged.caregiverReset = merged.caregiverReset || r.caregiverReset;
    if (r.consumedStep) {
      merged.consumedStep = true;
      break;
    }
  }
  return merged;
}

class Progress {
 public:
  Progress(bool enabled, std::int64_t total)
      : enabled_(enabled && isatty(2)), total_(std::max<std::int64_t>(total, 1)) {}
  void update(std::int64_t done, double lastEval) {
    if (!enabled_) return;
    const int pct = static_cast<int>(100 * done / total_);
    if (pct == last_) return;
    last_ = pct;
    const int bar = pct / 4;
    std::fprintf(stderr, "\r[%-25s] %3d%%  step %lld/%lld  eval %+.2f",
                 std::string(static_cast<std::size_t>(bar), '=').c_str(), pct, static_cast<long long>(done),
                 static_cast<long long>(total_), lastEval);
    std::fflush(stderr);
  }
  ~Progress() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  std::int64_t total_;
  int last_ = -1;
};

}  // namespace

namespace {

nlohmann::json configJson(const PreparedProgram& lp, const ExperimentConfig& config,
                          const sim::SimulatorOptions& simOptions, int task) {
  return {{"file", lp.path()},
          {"domain", lp.graph().domain},
          {"task", lp.graph().tasks[static_cast<std::size_t>(task)].name},
          {"approach", toString(config.approach.kind)},
          {"epsilon", config.approach.epsilon},
          {"replan", config.approach.replan},
          {"seed", config.seed},
          {"steps", config.steps},
          {"eval_every", config.evalEvery},
          {"eval_tasks", config.evalTasks},
          {"max_eval_episode_steps", config.maxEvalEpisodeSteps},
          {"dt", config.dt},
          {"nonstationary", config.nonstationary},
          {"adaptation", toString(config.adaptation)},
          {"shift_every", simOptions.shiftEvery},
          {"unsatisfiable_stock_probability", simOptions.unsatisfiableStockProbability},
          {"initial_profile", config.initialProfile},
          {"periodic_reset_every", config.periodicResetEvery},
          {"solver",
           {{"max_iters", config.solverOptions.maxIters},
            {"num_improvements", config.solverOptions.numImprovements},
            {"max_improvement_attempts", config.solverOptions.maxImprovementAttempts},
            {"memory_size", config.solverOptions.memorySize},
            {"memory", config.solverOptions.memoryPolicy == solver::MemoryPolicy::Solutions ? "solutions" : "checks"}}},
          {"text_backend", textpref::textBackendJson(config.textBackend.get())}};
}

std::string trainHeader() {
  return "step,execution_time,user_satisfaction,env_video_should_pause,solve_outcome,solver_iterations,replanned,"
         "labels_learned\n";
}

std::string evalHeader(int evalTasks, const std::vector<std::string>& preferences) {
  std::string h = "training_step,training_execution_time";
  for (int i = 0; i < evalTasks; ++i) h += fmt::format(",eval_episode_{}_user_satisfaction", i);
  h += ",eval_mean_user_satisfaction,eval_task_success_rate,eval_preferences_met_rate,eval_replans,"
       "eval_requests_solved_rate,eval_plans_executed_rate,eval_dry_run_mismatches";
  for (const auto& p : preferences) h += fmt::format(",eval_{}_met_rate", p);
  return h + "\n";
}

// Everything one trial carries from step to step; a checkpoint saves exactly this (Checkpoint.h).
struct Trial {
  Trial(const PreparedProgram& lp_, const ExperimentConfig& config_, RunOutput& out_,
        std::unique_ptr<sim::DomainSimulator> world, std::size_t task)
      : lp(lp_),
        config(config_),
        out(out_),
        taskIdx(task),
        trainWorld(std::move(world)),
        user(lp_.graph(), config_.textBackend),
        trainSolver(config_.solverOptions, deriveSeed(config_.seed, 1)),
        approachRng(deriveSeed(config_.seed, 2)),
        learning(learns(config_.approach)),
        fallback(fallsBack(config_.approach)) {}

  const PreparedProgram& lp;
  const ExperimentConfig& config;
  RunOutput& out;
  std::size_t taskIdx;
  RecordingSimulator trainWorld;
  std::unique_ptr<sim::DomainSimulator> evalWorld;
  model::UserModel user;
  solver::Solver trainSolver;
  rt::Rng approachRng;
  bool learning, fallback;
  ExperimentResult result;
  std::vector<sim::ActionCall> calls;  // the current plan's calls, and the next one to execute
  std::size_t next = 0;
  StepWorld planWorld;      // the solution and observation the current calls come from: what feedback is about
  bool planOpen = false;    // the current plan is being executed and not yet counted (Competence)
  bool planDryRun = false;  // it was dry-run before it was accepted
};

// Counts how a plan's execution ended once a step shows it: a failed action, its task done, or its calls used up.
void countExecution(Competence& c, bool& open, bool dryRun, const sim::StepResult& r, bool callsLeft) {
  if (!open) return;
  if (r.taskFailed) {
    ++c.failed;
    if (dryRun) ++c.dryRunMismatches;
    open = false;
  } else if (r.taskDone || !callsLeft) {
    ++c.executed;
    open = false;
  }
}

// Every plan with a Solved result was re-checked (Planner.h); a refused one is counted with its first violation.
void countRecheck(ExperimentResult& result, const Plan& plan) {
  if (!plan.rechecked) return;
  ++result.rechecks;
  if (plan.recheck.holds()) return;
  if (result.recheckViolations++ == 0) result.firstRecheckViolation = plan.recheck.violations.front();
}

// The record of what the robot did (motions.jsonl) also marks, for robot domains (a program with a world), each
// plan the runtime accepted, before its motions, and each time the robot was put back without a motion (an
// evaluation episode's start, a caregiver's reset): `cbtl audit` checks that between those the robot moved only by
// recorded motions, and tells the plans a dry run accepted apart (RunDirectory.h).
bool recordsRobot(const Trial& tr) { return tr.config.recordMotions && !tr.lp.worldPath().empty(); }

std::string planLine(const std::string& where, const Plan& plan) {
  nlohmann::json calls = nlohmann::json::array();
  for (const sim::ActionCall& c : plan.calls) calls.push_back(c.name);
  return fmt::format(R"({{{},"plan":{{"calls":{},"dry_run":{}}}}})", where, calls.dump(), plan.dryRun()) + "\n";
}

void evaluate(Trial& tr, std::int64_t step) {
  const ExperimentConfig& config = tr.config;
  const PreparedProgram& lp = tr.lp;
  EvalPoint point;
  point.step = step;
  model::UserModel evalUser = tr.user;  // the evaluation agent loads the training agent's models
  // Every checkpoint's evaluation starts from the same solver state, so what it measures depends on the models
  // at this step only, not on how many evaluations came before (a solver remembers satisfying values).
  solver::Solver evalSolver(config.solverOptions, evaluationSolverSeed(config.seed));
  int successes = 0, satisfied = 0;
  for (int i = 0; i < config.evalTasks; ++i) {
    tr.evalWorld->reset(evaluationTaskSeed(config.seed, i));
    if (recordsRobot(tr))
      tr.out.motionLine(fmt::format(R"({{"phase":"eval","step":{},"task":{},"reset":"episode"}})", step, i) + "\n");
    double satisfaction = 0;
    bool done = false, failed = false;
    std::int64_t steps = 0;
    while (!done && steps < config.maxEvalEpisodeSteps) {
      lp.syncWorld(*tr.evalWorld);
      const auto obs = observationVector(lp.program(), tr.evalWorld->observe());
      Plan plan = makePlan(lp, lp.taskFor(*tr.evalWorld, tr.taskIdx), obs, evaluationChoice(), tr.fallback, evalSolver,
                           evalUser);
      countRecheck(tr.result, plan);
      if (plan.replanned) ++point.replans;
      ++point.competence.requests;
      if (plan.ok) ++point.competence.solved;
      if (!plan.ok || plan.calls.empty()) break;  // the robot cannot do this task: the episode fails
      if (recordsRobot(tr))
        tr.out.motionLine(planLine(fmt::format(R"("phase":"eval","step":{},"task":{})", step, i), plan));
      std::size_t next = 0;
      bool open = true;
      while (next < plan.calls.size() && !done && steps < config.maxEvalEpisodeSteps) {
        sim::StepResult r = executeStep(*tr.evalWorld, plan.calls, next);
        if (config.recordMotions)
          for (const auto& m : r.motions)
            tr.out.motionLine(fmt::format(R"({{"phase":"eval","step":{},"task":{},{}}})", step, i, m) + "\n");
        countExecution(point.competence, open, plan.dryRun(), r, next < plan.calls.size());
        if (r.consumedStep) ++steps;
        if (r.hasSatisfaction) satisfaction += r.satisfaction;
        for (const auto& [name, met] : r.preferences) {
          PreferenceTally& tally = point.preferences[name];
          tally.met += met ? 1 : 0;
          ++tally.judged;
        }
        for (const auto& [name, value] : r.measures) point.measures[name].add(value);
        done = r.taskDone;
        failed = failed || r.taskFailed;
      }
    }
    if (done && !failed) ++successes;
    if (done && !failed && satisfaction > 0) ++satisfied;
    point.satisfaction.push_back(satisfaction);
  }
  double sum = 0;
  for (double s : point.satisfaction) sum += s;
  point.mean = config.evalTasks > 0 ? sum / config.evalTasks : 0;
  point.taskSuccessRate = config.evalTasks > 0 ? static_cast<double>(successes) / config.evalTasks : 0;
  point.preferencesMetRate = config.evalTasks > 0 ? static_cast<double>(satisfied) / config.evalTasks : 0;
  if (tr.out.enabled()) {
    std::string row = fmt::format("{},{:.6g}", step, static_cast<double>(step) * config.dt);
    for (double s : point.satisfaction) row += fmt::format(",{:.6g}", s);
    row += fmt::format(",{:.6g},{:.6g},{:.6g},{},{:.6g},{:.6g},{}\n", point.mean, point.taskSuccessRate,
                       point.preferencesMetRate, point.replans, point.competence.solvedRate(),
                       point.competence.executedRate(), point.competence.dryRunMismatches);
    row.pop_back();  // the preferences' columns follow
    for (const auto& name : tr.trainWorld.judgedPreferences()) {
      auto it = point.preferences.find(name);
      row += it == point.preferences.end() || it->second.judged == 0 ? std::string(",nan")
                                                                     : fmt::format(",{:.6g}", it->second.rate());
    }
    tr.out.evalRow(row + "\n");
    tr.out.writeModel(step, tr.user.toJson());
    if (config.testHook) config.testHook("model", step);
  }
  tr.result.eval.add(point.competence);
  tr.result.evals.push_back(std::move(point));
}

void trainStep(Trial& tr, std::int64_t t) {
  const ExperimentConfig& config = tr.config;
  const PreparedProgram& lp = tr.lp;
  ExperimentResult& result = tr.result;
  if (config.nonstationary && config.adaptation == Adaptation::PeriodicReset && t > 0 &&
      t % config.periodicResetEvery == 0) {
    tr.user.reset();
  }
  std::string outcome;
  std::uint64_t iterations = 0;
  bool replanned = false;
  if (tr.next >= tr.calls.size()) {
    lp.syncWorld(tr.trainWorld);
    const auto obs = observationVector(lp.program(), tr.trainWorld.observe());
    Plan plan = makePlan(lp, lp.taskFor(tr.trainWorld, tr.taskIdx), obs,
                         trainingChoice(config.approach, tr.approachRng), tr.fallback, tr.trainSolver, tr.user);
    countRecheck(result, plan);
    ++result.trainSolves;
    iterations = plan.iterations;
    result.solverIterations += iterations;
    outcome = solver::toString(plan.solve.outcome);
    replanned = plan.replanned;
    if (plan.replanned) ++result.trainReplans;
    if (!plan.ok) ++result.trainSolveFailures;
    ++result.train.requests;
    if (plan.ok) ++result.train.solved;
    tr.planOpen = plan.ok && !plan.calls.empty();
    tr.planDryRun = plan.dryRun();
    if (recordsRobot(tr) && plan.ok && !plan.calls.empty())
      tr.out.motionLine(planLine(fmt::format(R"("phase":"train","step":{})", t), plan));
    tr.calls = plan.ok ? std::move(plan.calls) : std::vector<sim::ActionCall>{};
    tr.next = 0;
    tr.planWorld = StepWorld{plan.ok ? std::move(plan.solve.assignment) : std::vector<double>{}, obs};
  }
  sim::StepResult r = tr.next < tr.calls.size() ? executeStep(tr.trainWorld, tr.calls, tr.next) : tr.trainWorld.idle();
  if (config.recordMotions)
    for (const auto& m : r.motions) tr.out.motionLine(fmt::format(R"({{"phase":"train","step":{},{}}})", t, m) + "\n");
  countExecution(result.train, tr.planOpen, tr.planDryRun, r, tr.next < tr.calls.size());
  if (r.caregiverReset) ++result.train.caregiverResets;
  if (r.caregiverReset && recordsRobot(tr))
    tr.out.motionLine(fmt::format(R"({{"phase":"train","step":{},"reset":"caregiver"}})", t) + "\n");
  std::size_t labels = 0;
  if (tr.learning && !r.feedback.empty()) {
    // A label's feature is a query of the world (an occlusion score, a clearance): it is read in the state the user
    // judged, the one this step left (the arm at the configuration, holding what it holds then), not the state
    // the plan started from.
    lp.syncWorld(tr.trainWorld);
    const LearnReport report = lp.learner().learn(r.feedback, tr.user, tr.planWorld);
    labels = report.labels;
    if (!report.problems.empty())
      throw std::runtime_error("feedback does not fit its declaration: " + report.problems.front());
    if (!report.modelErrors.empty() && result.textModelErrors == 0)
      result.firstTextModelError = report.modelErrors.front();
    result.textModelErrors += static_cast<std::int64_t>(report.modelErrors.size());
    if (config.recordFeedback) result.feedback.push_back({t, r.feedback});
  }
  if (r.preferencesChanged && config.nonstationary && config.adaptation == Adaptation::UserReset) tr.user.reset();
  if (r.taskDone) {
    if (!r.taskFailed) ++result.mealsServed;
    // The task is over (done or failed): calls left in its plan belong to no request.
    tr.calls.clear();
    tr.next = 0;
  }
  if (r.hasSatisfaction) result.trainSatisfaction += r.satisfaction;
  if (tr.out.enabled()) {
    tr.out.trainRow(fmt::format("{},{:.6g},{},False,{},{},{},{}\n", t, static_cast<double>(t) * config.dt,
                                r.hasSatisfaction ? fmt::format("{}", r.satisfaction) : std::string("nan"), outcome,
                                iterations, replanned ? 1 : 0, labels));
  }
  if (config.testHook) config.testHook("step", t);
}

void saveCheckpoint(Trial& tr, std::int64_t step) {
  if (!tr.out.enabled()) return;
  Checkpoint cp;
  cp.step = step;
  cp.worldCalls = tr.trainWorld.calls();
  cp.trainSolver = tr.trainSolver.saveState();
  cp.profile = nlohmann::json::parse(tr.user.toJson());
  cp.approachRng = tr.approachRng.saveState();
  const rt::StringTable& strings = tr.lp.program().strings();
  for (std::uint32_t i = 0; i < strings.size(); ++i) cp.strings.push_back(strings.name(i));
  cp.pending = tr.calls;
  cp.next = tr.next;
  cp.planWorld = tr.planWorld;
  cp.planOpen = tr.planOpen;
  cp.planDryRun = tr.planDryRun;
  cp.result = tr.result;
  tr.out.checkpoint(cp, tr.trainWorld.takeLog());
}

// Continues from a checkpoint: the state it saved, and the training world rebuilt by replaying its calls.
void restoreCheckpoint(Trial& tr, const Checkpoint& cp) {
  tr.trainWorld.replay(tr.out.worldLog(), tr.out.worldLogPath());
  if (tr.trainWorld.calls() != cp.worldCalls) {
    throw RunDirectoryError(fmt::format("'{}' holds {} world calls, its checkpoint {}; the run cannot be resumed",
                                        tr.out.worldLogPath(), tr.trainWorld.calls(), cp.worldCalls));
  }
  tr.trainSolver.restoreState(cp.trainSolver);
  tr.user.fromJson(cp.profile.dump(), tr.out.dir() + "/checkpoint.json");
  if (!tr.approachRng.restoreState(cp.approachRng))
    throw RunDirectoryError("the checkpoint's approach RNG state is malformed");
  rt::StringTable& strings = tr.lp.program().strings();
  for (std::uint32_t i = 0; i < cp.strings.size(); ++i) {
    if (strings.intern(cp.strings[i]) != i) throw RunDirectoryError("the checkpoint's texts do not fit this program");
  }
  tr.calls = cp.pending;
  tr.next = cp.next;
  tr.planWorld = cp.planWorld;
  tr.planOpen = cp.planOpen;
  tr.planDryRun = cp.planDryRun;
  tr.result = cp.result;
}

}  // namespace

ExperimentResult runExperiment(const PreparedProgram& lp, const SimulatorFactory& factory,
                               const ExperimentConfig& config) {
  const int task = lp.taskIndex(config.task);
  if (task < 0)
    throw std::runtime_error(config.task.empty() ? "the program has no task"
                                                 : fmt::format("no task named '{}'", config.task));
  if (config.evalEvery <= 0) throw std::runtime_error("--eval-every must be positive");
  if (config.steps < 0) throw std::runtime_error("--steps must not be negative");
  if (config.nonstationary && config.adaptation == Adaptation::PeriodicReset && config.periodicResetEvery <= 0)
    throw std::runtime_error("--periodic-reset-every must be positive");

  sim::SimulatorOptions simOptions = config.simulator;
  if (config.nonstationary && config.adaptation == Adaptation::UserReset) simOptions.announceShifts = true;
  textpref::beginRunFaults(config.textBackend.get());
  // The world first: eval.csv has a column per preference it judges.
  auto world = factory(simOptions, config.seed);
  if (!world) throw std::runtime_error(fmt::format("no simulator for domain '{}'", lp.graph().domain));
  RunOutput out(config.outDir, config.runMode, configJson(lp, config, simOptions, task), trainHeader(),
                evalHeader(config.evalTasks, world->judgedPreferences()));
  out.hook = config.testHook;
  if (out.completed()) {  // --resume of a complete run
    ExperimentResult done = *out.completed();
    done.finishedEarlier = true;
    done.recordedSeconds = out.recordedSeconds();
    return done;
  }
  // From here on the run folder exists: llm.json is written however the run ends (an exception leaving it,
  // SIGINT/SIGTERM through cbtl's interrupt handler), not only at its normal end below (textpref/RunReport.h).
  std::optional<textpref::LlmReportGuard> llmReport;
  if (out.enabled()) llmReport.emplace(out.dir(), config.textBackend.get());
  Trial tr(lp, config, out, std::move(world), static_cast<std::size_t>(task));
  std::int64_t start = 0;
  if (out.resumeFrom()) {
    restoreCheckpoint(tr, *out.resumeFrom());
    start = out.resumeFrom()->step;
  } else if (!config.initialProfileJson.empty()) {
    tr.user.fromJson(config.initialProfileJson, config.initialProfile);
  } else if (!config.initialProfile.empty()) {
    tr.user.load(config.initialProfile);
  }
  tr.evalWorld = tr.trainWorld.makeEvaluationTwin();

  Progress progress(config.progress, config.steps);
  for (std::int64_t t = start; t <= config.steps; ++t) {
    const bool checkpointHere = t % config.evalEvery == 0 || t == config.steps;
    if (checkpointHere &&
        !(out.resumeFrom() && t == start)) {  // a resumed run starts after its checkpoint's evaluation
      evaluate(tr, t);
      saveCheckpoint(tr, t);
    }
    if (t == config.steps) break;
    trainStep(tr, t);
    progress.update(t + 1, tr.result.evals.empty() ? 0 : tr.result.evals.back().mean);
  }
  tr.result.llmFaults = textpref::runFaults(config.textBackend.get());
  if (out.enabled()) {
    if (auto s = textpref::writeLlmReport(out.dir(), config.textBackend.get(), tr.result.llmFaults); !s.ok()) {
      throw std::runtime_error(s.error().describe());
    }
    llmReport->finish();
  }
  tr.result.finalProfile = tr.user.toJson();
  tr.result.finalLabels = tr.user.dataCount();
  out.finish(tr.result.finalProfile, tr.result);
  return tr.result;
}

}  // namespace cbtl::approach
