#include "app/SimulatorCheck.h"

#include "app/PlanReport.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <stdexcept>

namespace cbtl::app {
namespace {

std::string describe(const sim::StepResult& r) {
  std::string s = r.status == sim::ActionStatus::Ignored ? "ignored" : "applied";
  if (r.consumedStep) s += ", step";
  if (r.taskDone) s += r.taskFailed ? ", done (failed)" : ", done";
  if (r.hasSatisfaction) s += fmt::format(", satisfaction {:+g}", r.satisfaction);
  if (!r.feedback.empty())
    s += fmt::format(", {} feedback event{}", r.feedback.size(), r.feedback.size() == 1 ? "" : "s");
  if (!r.message.empty()) s += " (" + r.message + ")";
  return s;
}

// The exercise proper; `doing` always says which request is under way, for the report of an exception.
class Exercise {
 public:
  Exercise(const LoadedProgram& lp, sim::DomainSimulator& world, const std::vector<std::string>& actions,
           std::uint64_t seed, const solver::SolverOptions& options, SimulatorCheckReport& report)
      : lp_(lp),
        world_(world),
        actions_(actions),
        seed_(seed),
        solver_(options, seed),
        user_(lp.graph()),
        report_(report) {}

  void run(int maxRequests) {
    for (int i = 0; i < maxRequests && !(allActed() && report_.sawDone); ++i) planAndAct(world_, false);
    doing_ = "idle";
    report_.log.push_back("idle: " + describe(world_.idle()));
    report_.idled = true;
    doing_ = "twin";
    std::unique_ptr<sim::DomainSimulator> twin = world_.makeEvaluationTwin();
    if (!twin) throw std::runtime_error("the simulator made no evaluation twin");
    doing_ = fmt::format("reset of the twin (seed {})", seed_ + 1);
    twin->reset(seed_ + 1);
    report_.log.push_back(fmt::format("twin: reset seed {}", seed_ + 1));
    planAndAct(*twin, true);
    doing_ = "observe (the training world, after the twin's requests)";
    (void)world_.observe();
    report_.twinChecked = true;
  }

  const std::string& doing() const { return doing_; }

 private:
  bool allActed() const {
    return std::all_of(actions_.begin(), actions_.end(),
                       [&](const std::string& a) { return report_.actsByName.count(a) > 0; });
  }

  // One request: observe, plan, act its calls (only the first in a twin); idle when it is not solved.
  void planAndAct(sim::DomainSimulator& world, bool twin) {
    const char* which = twin ? "twin" : "world";
    doing_ = fmt::format("observe ({})", which);
    lp_.syncWorld(world);
    const std::vector<double> obs = approach::observationVector(lp_.program(), world.observe());
    const std::size_t task = lp_.taskFor(world, 0);
    doing_ = fmt::format("planning task '{}' ({})", lp_.graph().tasks.at(task).name, which);
    approach::Plan plan =
        approach::makePlan(lp_, task, obs, approach::CspChoice{}, false, solver_, user_);  // hard constraints only
    if (!plan.ok || plan.calls.empty()) {
      ++report_.plansUnsolved;
      report_.log.push_back(fmt::format("{}: task '{}' not solved ({}); idle", which, lp_.graph().tasks.at(task).name,
                                        solver::toString(plan.solve.outcome)));
      doing_ = fmt::format("idle ({})", which);
      report_.log.push_back("idle: " + describe(world.idle()));
      report_.idled = true;
      return;
    }
    ++report_.plansSolved;
    for (const sim::ActionCall& call : plan.calls) {
      doing_ = fmt::format("act {} ({})", renderCall(call), which);
      const sim::StepResult r = world.act(call);
      if (r.status == sim::ActionStatus::UnknownAction)
        throw std::runtime_error(fmt::format("the simulator answered status \"unknown\": {}", r.message));
      ++report_.actsByName[call.name];
      report_.log.push_back(fmt::format("{}act {}: {}", twin ? "twin: " : "", renderCall(call), describe(r)));
      if (r.taskDone && !twin) report_.sawDone = true;
      if (twin || r.taskDone) break;
    }
  }

  const LoadedProgram& lp_;
  sim::DomainSimulator& world_;
  const std::vector<std::string>& actions_;
  std::uint64_t seed_;
  solver::Solver solver_;
  model::UserModel user_;
  SimulatorCheckReport& report_;
  std::string doing_ = "the first request";
};

}  // namespace

SimulatorCheckReport exerciseSimulator(const LoadedProgram& lp, sim::DomainSimulator& world,
                                       const std::vector<std::string>& actions, std::uint64_t seed,
                                       const solver::SolverOptions& options, int maxRequests) {
  SimulatorCheckReport report;
  Exercise exercise(lp, world, actions, seed, options, report);
  try {
    exercise.run(maxRequests);
  } catch (const std::exception& e) {
    report.violation = fmt::format("{}: {}", exercise.doing(), e.what());
  }
  for (const std::string& a : actions) {
    if (!report.actsByName.count(a)) report.notExercised.push_back(a);
  }
  return report;
}

}  // namespace cbtl::app
