// StudySession.h — one participant of the web study (`cbtl study serve`), meal by meal, driven by what they answer.
//
// For the current meal (paperMeals(), in order) the session shows what each approach (studyApproaches(): CBTL
// and No Personalization) would do, as Option A and Option B in an order drawn per meal (the paper randomized
// it), and the configurations CBTL asks "would the arm there block your view?" about: the above-plate
// configuration of the choice it shows, with the plate where that choice puts it, and, as the paper's study
// did, the one its exploring CSP is least sure of (FeedingStudy.h). Each comes with the world state to render
// from the participant's eyes (the user_view camera) and its occlusion score (for the analysis; never shown).
// answer() carries both choices out in their worlds (so the next meal starts where this one left the plate),
// judges them by the answers, lets CBTL learn from the answers (answerMeal) and moves to the next meal.
//
// Determinism: every offer depends only on the program, the options, the participant number and the answers
// given so far, so a restarted server rebuilds a session by feeding it the stored answers again.
#pragma once

#include "domains/feeding/FeedingStudy.h"
#include "robot/world/WorldState.h"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::domains::feeding {

struct ViewQuestion {
  world::ArmConfig conf{};
  world::WorldState state;  // the scene as the participant would see it: the plate placed, the arm at conf
  double occlusion = 0;     // the occlusion score from the participant's eyes (Occlusion.h)
};

struct MealPresentation {
  std::size_t meal = 0;                     // index into paperMeals()
  std::map<std::string, MealOffer> offers;  // by approach
  std::array<std::string, 2> options;       // the approaches shown as Option A and Option B
  std::vector<ViewQuestion> views;          // CBTL's questions, in the order they are asked
};

// What the participant said about one meal; `blocked` has one entry per view question, in order.
struct ParticipantAnswers {
  BiteIdeals ideals;
  std::vector<bool> blocked;
};

class StudySession {
 public:
  // Participant `participant` of a study with these options (seed, solver, text backend). `lp` and `facts` must
  // outlive the session; `lp` must be the Feeding program.
  StudySession(const approach::PreparedProgram& lp, const ProgramFacts& facts, const StudyOptions& options,
               int participant);

  bool finished() const { return meal_ >= paperMeals().size(); }
  std::size_t meal() const { return meal_; }  // the current meal's index; paperMeals().size() when finished

  // The current meal as shown (computed once per meal). std::logic_error when finished.
  const MealPresentation& current();

  // Why answer() would refuse these answers about the current meal (an ideal outside the meal's choices, a count
  // of view answers other than the questions'), or nothing when it would take them. std::logic_error when finished.
  std::optional<std::string> check(const ParticipantAnswers& answers);

  // Takes the answers about the current meal and moves to the next. Returns each approach's choice as the answers
  // judge it. std::invalid_argument (nothing changes) for answers check() refuses; std::logic_error when finished.
  std::map<std::string, MealChoice> answer(const ParticipantAnswers& answers);

  // What CBTL has learned so far (the first of studyApproaches()).
  const model::UserModel& learnerModel() const { return arms_.front().model; }

  // Solutions re-checked before execution and refused, over every meal so far.
  const StudyResult& tally() const { return tally_; }

 private:
  const approach::PreparedProgram& lp_;
  int participant_;
  std::uint64_t seed_;
  std::vector<StudyArm> arms_;
  std::size_t meal_ = 0;
  std::optional<MealPresentation> current_;
  StudyResult tally_;
};

}  // namespace cbtl::domains::feeding
