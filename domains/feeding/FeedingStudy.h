// FeedingStudy.h — the paper's web study with simulated participants: five meals (paperMeals(), FeedingSimulator.h),
// CBTL against No Personalization, CBTL learning from each participant's answers between meals.
//
// Per participant n (FeedingUser::participant(n)) and per meal, in order, each approach gets its own world (the
// same start for both: FeedingSimulator reset with the participant's seed, then the meal served) and its own
// model, and:
//   1. solves feedBite the way the robot shows what it would do (the evaluation CSP, approach/Approach.h
//      evaluationChoice: hard and learned constraints, the task's cost) and carries the plan out in its world,
//      which judges the choice as the participant would answer the study's questions: their ideal dip, ready
//      signal and verbosity, and whether the configurations the robot chose block their view (the simulator's
//      bite answers, StepResult::preferences);
//   2. CBTL only: learns from those answers, and, as the study's "would your view be blocked?" pictures, also
//      asks about the above-plate configuration its exploring CSP (trainingChoice of cbtl: the most uncertain
//      one) chooses in the same state, and learns from that answer too (FeedingSimulator::viewAnswer).
// No Personalization never learns. A meal's plate starts where the previous meal's plan left it.
// Determinism: every random choice derives from (seed, participant), so a participant's results do not depend on
// how many others run or in which order.
#pragma once

#include "domains/ProgramFacts.h"
#include "domains/feeding/BiteAnswers.h"
#include "domains/feeding/FeedingPlanReading.h"
#include "domains/feeding/FeedingSimulator.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/PreparedProgram.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Solver.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::textpref {
class TextBackend;
}

namespace cbtl::domains::feeding {

struct StudyOptions {
  int participants = 60;  // participants firstParticipant .. firstParticipant + participants - 1
  int firstParticipant = 0;
  std::uint64_t seed = 0;
  bool askExploringView = true;  // step 2's extra question (off: CBTL learns from the shown choice alone)
  solver::SolverOptions solver;
  std::shared_ptr<const textpref::TextBackend> textBackend;  // null: the offline descriptor model
};

// The two approaches of the study, in this order.
inline const std::vector<std::string>& studyApproaches() {
  static const std::vector<std::string> names = {"cbtl", "no-personalization"};
  return names;
}
// The preferences a meal's choice is judged on (the bite's, FeedingSimulator::judgedPreferences).
inline const std::vector<std::string>& studyPreferences() {
  static const std::vector<std::string> names = {"bite", "dip", "signal", "verbosity", "view"};
  return names;
}

// One approach's choice for one meal of one participant.
struct MealChoice {
  bool solved = false;                      // the CSP was solved and its plan ran to the end of the bite
  std::map<std::string, bool> preferences;  // studyPreferences(), as the participant judged them
  std::string dip, signal, verbosity;       // the choices (Dip entry, ReadySignal, Verbosity member)
  double occlusion = 0;                     // occlusion score of the above-plate configuration chosen
  int met() const;                          // how many of dip, signal, verbosity, view were met
};

struct ParticipantMeals {
  int participant = 0;
  std::vector<std::map<std::string, MealChoice>> meals;  // per meal, by approach
};

// Per meal, over all participants.
struct MealSummary {
  Meal meal;
  std::map<std::string, std::map<std::string, approach::PreferenceTally>> met;  // approach -> preference -> tally
  int cbtlBetter = 0, tied = 0, cbtlWorse = 0;  // participants by who met more of dip, signal, verbosity, view
};

struct StudyResult {
  std::vector<ParticipantMeals> participants;
  std::vector<MealSummary> meals;  // the five, in order
  std::int64_t rechecks = 0, recheckViolations = 0;
};

// A participant's two approaches after some meals: what each has learned and the world it left.
struct StudyArm {
  std::string approach;
  bool learns = false;
  std::unique_ptr<FeedingSimulator> world;
  model::UserModel model;
  solver::Solver solver;           // the choices it shows
  solver::Solver exploringSolver;  // CBTL's question about its most uncertain view (apart, so that meal 1's shown
                                   // choices are the same for both approaches)
  StudyArm(std::string name, bool learning, std::unique_ptr<FeedingSimulator> sim, const ir::ConstraintGraph& graph,
           const StudyOptions& options, std::uint64_t solverSeed);
};

// Participant n's seed in a study of seed `seed`: their worlds' start and every random choice made for them
// (streams of approach::deriveSeed).
std::uint64_t participantSeed(std::uint64_t seed, int participant);

// Makes participant n's two arms (studyApproaches()), both worlds reset with the participant's seed.
std::vector<StudyArm> makeStudyArms(const approach::PreparedProgram& lp, const ProgramFacts& facts,
                                    const StudyOptions& options, int participant);
// What runPlan calls for an arm that learns (none for one that does not): the world is synced to the program's
// built-ins and the events learned at once, so that a label's feature (the occlusion score of the configuration,
// with what the arm holds there) is read as the user judged it. Throws std::runtime_error for events that do not
// fit their declarations.
FeedbackHandler learnAsJudged(const approach::PreparedProgram& lp, StudyArm& arm, const approach::StepWorld& world);

// What one arm would do at meal `meal` (an index into paperMeals()), decided and not yet carried out: the meal is
// served in the arm's world, the choice it shows is solved (step 1's CSP) and, for an arm that learns, the
// above-plate configuration its exploring CSP is least sure of (step 2's question). Throws rt::RuntimeError or
// std::runtime_error for a program that does not fit the Feeding simulator.
struct MealOffer {
  std::size_t meal = 0;
  std::vector<double> observation;  // the CSP's observation, in the program's order
  approach::Plan shown;
  PlanChoices read;                               // the shown plan's choices (when it was solved)
  std::optional<world::ArmConfig> exploringConf;  // the learner's most uncertain view
};
MealOffer offerMeal(const approach::PreparedProgram& lp, StudyArm& arm, std::size_t meal, StudyResult& tally);

// Runs meal `meal` for one arm with a simulated participant: offerMeal, the shown plan carried out in the arm's
// world (whose participant judges it and, for a learner, teaches it as it goes), then the exploring view's
// question answered by the participant.
MealChoice runStudyMeal(const approach::PreparedProgram& lp, StudyArm& arm, std::size_t meal, StudyResult& tally);

// A real participant's answers about one meal (the web study): the ideals (BiteAnswers.h) and, for each view they
// were shown, whether the arm there would block their view.
struct MealAnswers {
  BiteIdeals ideals;
  std::vector<std::pair<world::ArmConfig, bool>> views;  // (configuration shown, blocked)
};

// Carries `offer` out in the arm's world (so the next meal starts where this one left the plate; the world's own
// simulated participant is not listened to) and, for an arm that learns, learns what `answers` say about it: the
// bite's answers about the shown choice, then each view answer, each read in the world as it is after the meal.
// Returns the choice with the preferences the answers judge it by (dip, signal and verbosity against the ideals;
// view: the picture of the shown choice's above-plate configuration not called blocked). Throws std::invalid_argument
// for answers outside the meal's choices (checkIdeals), std::runtime_error as offerMeal.
MealChoice answerMeal(const approach::PreparedProgram& lp, StudyArm& arm, const MealOffer& offer,
                      const MealAnswers& answers);

// The whole study. `lp` must be the Feeding program (domains/feeding/feeding.cbtl or one with its tasks,
// variables and feedback events).
StudyResult runStudy(const approach::PreparedProgram& lp, const ProgramFacts& facts, const StudyOptions& options);

// study.csv: one row per participant, meal and approach (the choices, each preference met, the occlusion score).
std::string studyCsv(const StudyResult& result);

}  // namespace cbtl::domains::feeding
