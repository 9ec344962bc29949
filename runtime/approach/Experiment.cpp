#include "Experiment.h"

#include "Planner.h"
#include "ValueBridge.h"

#include "textpref/RunReport.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace cbtl::approach {

namespace fs = std::filesystem;

const char* toString(Adaptation a) {
  switch (a) {
    case Adaptation::NoAdapt: return "no-adapt";
    case Adaptation::UserReset: return "user-reset";
    case Adaptation::PeriodicReset: return "periodic-reset";
  }
  return "?";
}

std::optional<Adaptation> parseAdaptation(const std::string& name) {
  for (auto a : {Adaptation::NoAdapt, Adaptation::UserReset, Adaptation::PeriodicReset}) {
    if (name == toString(a)) return a;
  }
  return std::nullopt;
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

std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream) {
  // splitmix64 of the pair: well-mixed, independent streams from one run seed.
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

namespace {

void requireApplied(const sim::StepResult& r, const sim::ActionCall& call) {
  if (r.status == sim::ActionStatus::UnknownAction) {
    throw std::runtime_error(fmt::format("the simulator rejected action '{}': {}", call.name, r.message));
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
    if (r.hasSatisfaction) {
      merged.hasSatisfaction = true;
      merged.satisfaction += r.satisfaction;
    }
    merged.taskDone = merged.taskDone || r.taskDone;
    merged.taskFailed = merged.taskFailed || r.taskFailed;
    merged.preferencesChanged = merged.preferencesChanged || r.preferencesChanged;
    if (r.consumedStep) {
      merged.consumedStep = true;
      break;
    }
  }
  return merged;
}

class Progress {
 public:
  Progress(bool enabled, std::int64_t total) : enabled_(enabled && isatty(2)), total_(std::max<std::int64_t>(total, 1)) {}
  void update(std::int64_t done, double lastEval) {
    if (!enabled_) return;
    const int pct = static_cast<int>(100 * done / total_);
    if (pct == last_) return;
    last_ = pct;
    const int bar = pct / 4;
    std::fprintf(stderr, "\r[%-25s] %3d%%  step %lld/%lld  eval %+.2f", std::string(static_cast<std::size_t>(bar), '=').c_str(), pct,
                 static_cast<long long>(done), static_cast<long long>(total_), lastEval);
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

ExperimentResult runExperiment(const LoadedProgram& lp, const SimulatorFactory& factory, const ExperimentConfig& config) {
  const int task = lp.taskIndex(config.task);
  if (task < 0) throw std::runtime_error(config.task.empty() ? "the program has no task" : fmt::format("no task named '{}'", config.task));
  if (config.evalEvery <= 0) throw std::runtime_error("--eval-every must be positive");
  if (config.steps < 0) throw std::runtime_error("--steps must not be negative");

  sim::SimulatorOptions simOptions = config.simulator;
  if (config.nonstationary && config.adaptation == Adaptation::UserReset) simOptions.announceShifts = true;
  auto trainWorld = factory(simOptions, config.seed);
  if (!trainWorld) throw std::runtime_error(fmt::format("no simulator for domain '{}'", lp.graph().domain));
  auto evalWorld = trainWorld->makeEvaluationTwin();
  textpref::beginRunFaults(config.textBackend.get());

  const rt::Program& program = lp.program();
  model::UserModel user(lp.graph(), config.textBackend);
  if (!config.initialProfile.empty()) user.load(config.initialProfile);
  solver::Solver trainSolver(config.solverOptions, deriveSeed(config.seed, 1));
  solver::Solver evalSolver(config.solverOptions, deriveSeed(config.seed + 100000, 1));
  rt::Rng approachRng(deriveSeed(config.seed, 2));
  const bool learning = learns(config.approach);
  const bool fallback = fallsBack(config.approach);

  std::ofstream trainCsv, evalCsv;
  if (!config.outDir.empty()) {
    fs::create_directories(fs::path(config.outDir) / "models");
    trainCsv.open(fs::path(config.outDir) / "train.csv");
    evalCsv.open(fs::path(config.outDir) / "eval.csv");
    if (!trainCsv || !evalCsv) throw std::runtime_error(fmt::format("cannot write into '{}'", config.outDir));
    trainCsv << "step,execution_time,user_satisfaction,env_video_should_pause,solve_outcome,solver_iterations,replanned,"
                "labels_learned\n";
    evalCsv << "training_step,training_execution_time";
    for (int i = 0; i < config.evalTasks; ++i) evalCsv << ",eval_episode_" << i << "_user_satisfaction";
    evalCsv << ",eval_mean_user_satisfaction,eval_task_success_rate,eval_preferences_met_rate,eval_replans\n";
    nlohmann::json cfg = {{"file", lp.path()}, {"domain", lp.graph().domain}, {"task", lp.graph().tasks[static_cast<std::size_t>(task)].name},
                          {"approach", toString(config.approach.kind)}, {"epsilon", config.approach.epsilon},
                          {"replan", config.approach.replan}, {"seed", config.seed}, {"steps", config.steps},
                          {"eval_every", config.evalEvery}, {"eval_tasks", config.evalTasks},
                          {"max_eval_episode_steps", config.maxEvalEpisodeSteps}, {"dt", config.dt},
                          {"nonstationary", config.nonstationary}, {"adaptation", toString(config.adaptation)},
                          {"shift_every", simOptions.shiftEvery}, {"unsatisfiable_stock_probability", simOptions.unsatisfiableStockProbability},
                          {"solver", {{"max_iters", config.solverOptions.maxIters}, {"num_improvements", config.solverOptions.numImprovements},
                                      {"max_improvement_attempts", config.solverOptions.maxImprovementAttempts},
                                      {"memory_size", config.solverOptions.memorySize}}}};
    cfg["text_backend"] = textpref::textBackendJson(config.textBackend.get());
    std::ofstream(fs::path(config.outDir) / "config.json") << cfg.dump(2) << "\n";
  }

  ExperimentResult result;
  Progress progress(config.progress, config.steps);
  const auto taskIdx = static_cast<std::size_t>(task);

  auto evaluate = [&](std::int64_t step) {
    EvalPoint point;
    point.step = step;
    model::UserModel evalUser = user;  // the evaluation agent loads the training agent's models
    int successes = 0, satisfied = 0;
    for (int i = 0; i < config.evalTasks; ++i) {
      evalWorld->reset(evaluationTaskSeed(config.seed, i));
      double satisfaction = 0;
      bool done = false, failed = false;
      std::int64_t steps = 0;
      while (!done && steps < config.maxEvalEpisodeSteps) {
        lp.syncWorld(*evalWorld);
        const auto obs = observationVector(program, evalWorld->observe());
        Plan plan = makePlan(lp, lp.taskFor(*evalWorld, taskIdx), obs, evaluationChoice(), fallback, evalSolver, evalUser);
        if (plan.replanned) ++point.replans;
        if (!plan.ok || plan.calls.empty()) break;  // the robot cannot do this task: the episode fails
        std::size_t next = 0;
        while (next < plan.calls.size() && !done && steps < config.maxEvalEpisodeSteps) {
          sim::StepResult r = executeStep(*evalWorld, plan.calls, next);
          if (r.consumedStep) ++steps;
          if (r.hasSatisfaction) satisfaction += r.satisfaction;
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
    if (evalCsv.is_open()) {
      evalCsv << step << "," << fmt::format("{:.6g}", static_cast<double>(step) * config.dt);
      for (double s : point.satisfaction) evalCsv << "," << s;
      evalCsv << "," << fmt::format("{:.6g}", point.mean) << "," << fmt::format("{:.6g}", point.taskSuccessRate) << ","
              << fmt::format("{:.6g}", point.preferencesMetRate) << "," << point.replans << "\n";
      user.save((fs::path(config.outDir) / "models" / fmt::format("{}.json", step)).string());
    }
    result.evals.push_back(std::move(point));
  };

  std::vector<sim::ActionCall> calls;
  std::size_t next = 0;
  for (std::int64_t t = 0; t <= config.steps; ++t) {
    if (t % config.evalEvery == 0 || t == config.steps) evaluate(t);
    if (t == config.steps) break;
    if (config.nonstationary && config.adaptation == Adaptation::PeriodicReset && t > 0 && t % config.periodicResetEvery == 0) {
      user.reset();
    }
    std::string outcome;
    std::uint64_t iterations = 0;
    bool replanned = false;
    if (next >= calls.size()) {
      lp.syncWorld(*trainWorld);
      const auto obs = observationVector(program, trainWorld->observe());
      Plan plan = makePlan(lp, lp.taskFor(*trainWorld, taskIdx), obs, trainingChoice(config.approach, approachRng), fallback,
                           trainSolver, user);
      ++result.trainSolves;
      iterations = plan.solve.iterations + (plan.failedFull ? plan.failedFull->iterations : 0);
      result.solverIterations += iterations;
      outcome = solver::toString(plan.solve.outcome);
      replanned = plan.replanned;
      if (plan.replanned) ++result.trainReplans;
      if (!plan.ok) ++result.trainSolveFailures;
      calls = plan.ok ? std::move(plan.calls) : std::vector<sim::ActionCall>{};
      next = 0;
    }
    sim::StepResult r = next < calls.size() ? executeStep(*trainWorld, calls, next) : trainWorld->idle();
    std::size_t labels = 0;
    if (learning && !r.feedback.empty()) {
      const LearnReport report = lp.learner().learn(r.feedback, user);
      labels = report.labels;
      if (!report.problems.empty()) throw std::runtime_error("feedback does not fit its declaration: " + report.problems.front());
      if (!report.modelErrors.empty() && result.textModelErrors == 0) result.firstTextModelError = report.modelErrors.front();
      result.textModelErrors += static_cast<std::int64_t>(report.modelErrors.size());
    }
    if (r.preferencesChanged && config.nonstationary && config.adaptation == Adaptation::UserReset) user.reset();
    if (r.taskDone) {
      if (!r.taskFailed) ++result.mealsServed;
      // The task is over (done or failed): calls left in its plan belong to no request.
      calls.clear();
      next = 0;
    }
    if (r.hasSatisfaction) result.trainSatisfaction += r.satisfaction;
    if (trainCsv.is_open()) {
      trainCsv << t << "," << fmt::format("{:.6g}", static_cast<double>(t) * config.dt) << ","
               << (r.hasSatisfaction ? fmt::format("{}", r.satisfaction) : std::string("nan")) << ",False," << outcome << ","
               << iterations << "," << (replanned ? 1 : 0) << "," << labels << "\n";
    }
    progress.update(t + 1, result.evals.empty() ? 0 : result.evals.back().mean);
  }
  if (!config.outDir.empty()) user.save((fs::path(config.outDir) / "profile.json").string());
  result.llmFaults = textpref::runFaults(config.textBackend.get());
  if (!config.outDir.empty()) {
    if (auto s = textpref::writeLlmReport(config.outDir, config.textBackend.get(), result.llmFaults); !s.ok())
      throw std::runtime_error(s.error().describe());
  }
  return result;
}

}  // namespace cbtl::approach
