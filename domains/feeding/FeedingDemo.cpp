#include "domains/feeding/FeedingDemo.h"

#include "domains/feeding/FeedingActions.h"

#include "runtime/approach/Learner.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"

#include <fmt/format.h>

#include <stdexcept>

namespace cbtl::domains::feeding {

namespace {

std::vector<double> bodyXY(const FeedingSimulator& world, const char* body) {
  const auto& objects = world.worldState()->objects;
  auto it = objects.find(body);
  if (it == objects.end()) return {};
  return {it->second.position.x(), it->second.position.y()};
}

// One request of meal 5 for one arm: solve as the robot exploits, read the choices, let the observer look, carry
// the plan out, learn (CBTL).
DemoStep runDemoRequest(const approach::PreparedProgram& lp, StudyArm& arm, const std::string& request, int trial,
                        const DemoObserver& observer) {
  FeedingSimulator& world = *arm.world;
  DemoStep step;
  step.request = request;
  const std::size_t task = lp.taskFor(world, 0);
  step.task = lp.graph().tasks.at(task).name;
  step.plateFrom = bodyXY(world, "plate");
  step.drinkFrom = bodyXY(world, "drink");
  lp.syncWorld(world);
  const auto observation = approach::observationVector(lp.program(), world.observe());
  const approach::Plan plan =
      approach::makePlan(lp, task, observation, approach::evaluationChoice(), false, arm.solver, arm.model);
  if (!plan.ok) return step;
  const PlanChoices c = readPlanChoices(lp, task, plan.solve.assignment);
  if (c.plate) step.plateTo = *c.plate;
  if (c.drink) step.drinkTo = *c.drink;
  step.dip = c.dip;
  step.signal = c.signal;
  step.verbosity = c.verbosity;
  step.conf = c.abovePlateConf ? c.abovePlateConf : c.drinkConf;
  if (step.conf) {
    // Judged where the request will have put the plate and the drink (the drink is in the view when held out).
    const world::WorldState keep = *world.worldState();
    world.world().workspace().setState(demoStepState(world, step));
    step.occlusion = world.occlusionAt(*step.conf);
    world.world().workspace().setState(keep);
  }
  if (observer) observer(trial, arm.approach, step, world);
  const PlanRun run =
      runPlan(world, plan.calls, learnAsJudged(lp, arm, approach::StepWorld{plan.solve.assignment, observation}));
  step.solved = run.done && !run.failed;
  step.complaints = run.complaints;
  return step;
}

}  // namespace

world::WorldState demoStepState(FeedingSimulator& world, const DemoStep& step) {
  world::WorldState s = *world.worldState();
  const auto place = [&](const char* body, const std::vector<double>& xy) {
    auto it = s.objects.find(body);
    if (it == s.objects.end() || xy.size() != 2) return;
    it->second.position.x() = xy[0];
    it->second.position.y() = xy[1];
  };
  place("plate", step.plateTo);
  place("drink", step.drinkTo);
  if (!step.conf) return s;
  s.arm = *step.conf;
  // What the robot holds at that configuration: the utensil above the plate, or the drink, held as grasp("drink")
  // takes it where it stood.
  if (step.request.rfind("bite", 0) == 0) {
    s.held = world::Grasp{"utensil", world::Pose3::fromPosition({0, 0, kUtensilGraspDepth})};
  } else if (step.request.rfind("drink", 0) == 0 && s.objects.count("drink")) {
    s.held = world::Grasp{"drink", drinkInTool(s.objects.at("drink"))};
  }
  return s;
}

DemoResult runDemo(const approach::PreparedProgram& lp, const ProgramFacts& facts, const DemoOptions& options,
                   const DemoObserver& observer) {
  const std::size_t lastMeal = paperMeals().size() - 1;
  DemoResult result;
  result.meal = paperMeals()[lastMeal];
  result.threshold = FeedingUser::participant(static_cast<std::uint64_t>(options.participant)).occlusionThreshold;
  for (int t = 0; t < options.trials; ++t) {
    StudyOptions study = options.study;
    study.seed = options.seed + static_cast<std::uint64_t>(t);
    StudyResult unused;
    std::vector<StudyArm> arms = makeStudyArms(lp, facts, study, options.participant);
    DemoTrial trial;
    for (StudyArm& arm : arms) {
      for (std::size_t k = 0; k < lastMeal; ++k) runStudyMeal(lp, arm, k, unused);
      FeedingSimulator& world = *arm.world;
      world.serveMealNow(result.meal);
      if (!world.placeOnTable("plate", options.plateX, options.plateY))
        throw std::runtime_error(fmt::format("the demonstration's plate spot ({}, {}) is not on the meal's table",
                                             options.plateX, options.plateY));
      std::vector<DemoStep>& steps = trial.steps[arm.approach];
      for (const auto& request : demoRequests()) {
        // The caregiver puts the drink in front of the user; the robot is asked to prepare it (its own random
        // spot, FeedingSimulator, is overridden).
        if (world.request() == Request::Prepare && !world.placeOnTable("drink", options.drinkX, options.drinkY))
          throw std::runtime_error(fmt::format("the demonstration's drink spot ({}, {}) is not on the meal's table",
                                               options.drinkX, options.drinkY));
        steps.push_back(runDemoRequest(lp, arm, request, t, observer));
      }
    }
    result.trials.push_back(std::move(trial));
  }
  return result;
}

}  // namespace cbtl::domains::feeding
