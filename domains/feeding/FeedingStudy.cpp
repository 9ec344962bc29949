#include "domains/feeding/FeedingStudy.h"

#include <stdexcept>
#include "domains/feeding/FeedingPlanReading.h"
#include "runtime/approach/Learner.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"

#include <fmt/format.h>

#include <algorithm>

namespace cbtl::domains::feeding {

namespace {

void learnOrThrow(const approach::PreparedProgram& lp, StudyArm& arm, const std::vector<sim::FeedbackEvent>& events,
                  const approach::StepWorld& world) {
  if (events.empty()) return;
  const approach::LearnReport report = lp.learner().learn(events, arm.model, world);
  if (!report.problems.empty())
    throw std::runtime_error("feedback does not fit its declaration: " + report.problems.front());
}

std::size_t feedBiteTask(const approach::PreparedProgram& lp) {
  const int task = lp.taskIndex("feedBite");
  if (task < 0) throw std::runtime_error(lp.path() + ": the study needs the task feedBite");
  return static_cast<std::size_t>(task);
}

// The shown choice as the participant sees it, before anyone judges it.
MealChoice choiceOf(FeedingSimulator& world, const MealOffer& offer) {
  MealChoice choice;
  if (!offer.shown.ok) return choice;
  choice.dip = offer.read.dip;
  choice.signal = offer.read.signal;
  choice.verbosity = offer.read.verbosity;
  if (offer.read.abovePlateConf) choice.occlusion = world.occlusionAt(*offer.read.abovePlateConf);
  return choice;
}

void countRecheck(StudyResult& tally, const approach::Plan& plan) {
  if (!plan.rechecked) return;
  ++tally.rechecks;
  if (!plan.recheck.holds()) ++tally.recheckViolations;
}

}  // namespace

std::uint64_t participantSeed(std::uint64_t seed, int participant) {
  return approach::deriveSeed(seed, 7000 + static_cast<std::uint64_t>(participant));
}

FeedbackHandler learnAsJudged(const approach::PreparedProgram& lp, StudyArm& arm, const approach::StepWorld& world) {
  if (!arm.learns) return {};
  return [&lp, &arm, world](const std::vector<sim::FeedbackEvent>& events) {
    lp.syncWorld(*arm.world);
    learnOrThrow(lp, arm, events, world);
  };
}

int MealChoice::met() const {
  int n = 0;
  for (const char* name : {"dip", "signal", "verbosity", "view"}) {
    auto it = preferences.find(name);
    n += it != preferences.end() && it->second ? 1 : 0;
  }
  return n;
}

StudyArm::StudyArm(std::string name, bool learning, std::unique_ptr<FeedingSimulator> sim,
                   const ir::ConstraintGraph& graph, const StudyOptions& options, std::uint64_t solverSeed)
    : approach(std::move(name)),
      learns(learning),
      world(std::move(sim)),
      model(graph, options.textBackend),
      solver(options.solver, solverSeed),
      exploringSolver(options.solver, approach::deriveSeed(solverSeed, 2)) {}

std::vector<StudyArm> makeStudyArms(const approach::PreparedProgram& lp, const ProgramFacts& facts,
                                    const StudyOptions& options, int participant) {
  const std::uint64_t seed = participantSeed(options.seed, participant);
  sim::SimulatorOptions simOptions;
  simOptions.participant = participant;
  std::vector<StudyArm> arms;
  for (const auto& name : studyApproaches()) {
    arms.emplace_back(name, name == "cbtl", std::make_unique<FeedingSimulator>(facts, simOptions, seed), lp.graph(),
                      options, approach::deriveSeed(seed, 1));
  }
  return arms;
}

MealOffer offerMeal(const approach::PreparedProgram& lp, StudyArm& arm, std::size_t meal, StudyResult& tally) {
  FeedingSimulator& world = *arm.world;
  world.serveMealNow(paperMeals().at(meal));
  const std::size_t task = feedBiteTask(lp);
  lp.syncWorld(world);
  MealOffer offer;
  offer.meal = meal;
  offer.observation = approach::observationVector(lp.program(), world.observe());
  if (arm.learns) {
    rt::Rng unused(0);
    const approach::Plan exploring = approach::makePlan(
        lp, task, offer.observation, approach::trainingChoice({approach::ApproachKind::Cbtl}, unused), false,
        arm.exploringSolver, arm.model);
    countRecheck(tally, exploring);
    if (exploring.ok) offer.exploringConf = readConf(lp, task, exploring.solve.assignment, kAbovePlateConf);
  }
  offer.shown =
      approach::makePlan(lp, task, offer.observation, approach::evaluationChoice(), false, arm.solver, arm.model);
  countRecheck(tally, offer.shown);
  if (offer.shown.ok) offer.read = readPlanChoices(lp, task, offer.shown.solve.assignment);
  return offer;
}

MealChoice runStudyMeal(const approach::PreparedProgram& lp, StudyArm& arm, std::size_t meal, StudyResult& tally) {
  const MealOffer offer = offerMeal(lp, arm, meal, tally);
  FeedingSimulator& world = *arm.world;
  MealChoice choice = choiceOf(world, offer);
  if (offer.shown.ok) {
    const PlanRun run =
        runPlan(world, offer.shown.calls,
                learnAsJudged(lp, arm, approach::StepWorld{offer.shown.solve.assignment, offer.observation}));
    choice.solved = run.done && !run.failed;
    for (const auto& [name, met] : run.preferences) choice.preferences[name] = met;
  }
  if (arm.learns && offer.exploringConf) {
    // Asked with the arm back where the plan left it: the score is the configuration's (the utensil, stowed or
    // held, is not in the user's view), read in the world as it is now.
    lp.syncWorld(world);
    learnOrThrow(lp, arm, {world.viewAnswer(*offer.exploringConf)}, approach::StepWorld{{}, offer.observation});
  }
  return choice;
}

MealChoice answerMeal(const approach::PreparedProgram& lp, StudyArm& arm, const MealOffer& offer,
                      const MealAnswers& answers) {
  const Meal& meal = paperMeals().at(offer.meal);
  const BiteOffer bite{meal.food, meal.dips, offer.read.dip, offer.read.signal, offer.read.verbosity};
  if (offer.shown.ok) {
    if (auto problem = checkIdeals(bite, answers.ideals)) throw std::invalid_argument(*problem);
  }
  FeedingSimulator& world = *arm.world;
  MealChoice choice = choiceOf(world, offer);
  if (!offer.shown.ok) return choice;
  const PlanRun run = runPlan(world, offer.shown.calls);
  choice.solved = run.done && !run.failed;
  // The view preference is about the robot's own choice: a picture of another configuration (the exploring CSP's
  // question) says what the participant would mind, not what this choice did.
  bool blocked = false;
  for (const auto& [conf, isBlocked] : answers.views)
    blocked = blocked || (isBlocked && offer.read.abovePlateConf && conf == *offer.read.abovePlateConf);
  choice.preferences = {{"dip", bite.dip == answers.ideals.dip},
                        {"signal", bite.signal == answers.ideals.signal},
                        {"verbosity", bite.verbosity == answers.ideals.verbosity},
                        {"view", !blocked}};
  choice.preferences["bite"] = choice.met() == 4;
  if (!arm.learns) return choice;
  lp.syncWorld(world);
  learnOrThrow(lp, arm, biteAnswerEvents(bite, answers.ideals),
               approach::StepWorld{offer.shown.solve.assignment, offer.observation});
  std::vector<sim::FeedbackEvent> views;
  for (const auto& [conf, isBlocked] : answers.views) views.push_back(viewAnswerEvent(conf, isBlocked));
  learnOrThrow(lp, arm, views, approach::StepWorld{{}, offer.observation});
  return choice;
}

StudyResult runStudy(const approach::PreparedProgram& lp, const ProgramFacts& facts, const StudyOptions& options) {
  StudyResult result;
  for (const Meal& meal : paperMeals()) result.meals.push_back(MealSummary{meal, {}, 0, 0, 0});
  for (int p = options.firstParticipant; p < options.firstParticipant + options.participants; ++p) {
    std::vector<StudyArm> arms = makeStudyArms(lp, facts, options, p);
    ParticipantMeals record{p, {}};
    for (std::size_t k = 0; k < paperMeals().size(); ++k) {
      std::map<std::string, MealChoice> choices;
      for (StudyArm& arm : arms) choices[arm.approach] = runStudyMeal(lp, arm, k, result);
      MealSummary& summary = result.meals[k];
      for (const auto& [name, choice] : choices) {
        for (const auto& pref : studyPreferences()) {
          approach::PreferenceTally& t = summary.met[name][pref];
          auto it = choice.preferences.find(pref);
          t.met += it != choice.preferences.end() && it->second ? 1 : 0;
          ++t.judged;
        }
      }
      const int cbtl = choices["cbtl"].met(), np = choices["no-personalization"].met();
      (cbtl > np ? summary.cbtlBetter : cbtl == np ? summary.tied : summary.cbtlWorse) += 1;
      record.meals.push_back(std::move(choices));
    }
    result.participants.push_back(std::move(record));
  }
  return result;
}

std::string studyCsv(const StudyResult& result) {
  std::string out = "participant,meal,approach,solved,dip,signal,verbosity,occlusion";
  for (const auto& pref : studyPreferences()) out += fmt::format(",{}_met", pref);
  out += "\n";
  for (const auto& p : result.participants) {
    for (std::size_t k = 0; k < p.meals.size(); ++k) {
      for (const auto& name : studyApproaches()) {
        const MealChoice& c = p.meals[k].at(name);
        out += fmt::format("{},{},{},{},{},{},{},{:.6g}", p.participant, k + 1, name, c.solved ? 1 : 0, c.dip, c.signal,
                           c.verbosity, c.occlusion);
        for (const auto& pref : studyPreferences()) {
          auto it = c.preferences.find(pref);
          out += it == c.preferences.end() ? std::string(",") : fmt::format(",{}", it->second ? 1 : 0);
        }
        out += "\n";
      }
    }
  }
  return out;
}

}  // namespace cbtl::domains::feeding
