#include "domains/feeding/StudySession.h"

#include "domains/feeding/FeedingActions.h"
#include "runtime/core/Rng.h"

#include <fmt/format.h>

#include <stdexcept>

namespace cbtl::domains::feeding {

namespace {

// The scene the participant judges a bite's configuration in: the plate where the shown choice puts it, the arm at
// `conf` holding the utensil (as it does above the plate).
world::WorldState biteViewState(FeedingSimulator& world, const PlanChoices& shown, const world::ArmConfig& conf) {
  world::WorldState s = *world.worldState();
  if (auto it = s.objects.find("plate"); it != s.objects.end() && shown.plate && shown.plate->size() == 2) {
    it->second.position.x() = (*shown.plate)[0];
    it->second.position.y() = (*shown.plate)[1];
  }
  s.arm = conf;
  s.held = world::Grasp{"utensil", world::Pose3::fromPosition({0, 0, kUtensilGraspDepth})};
  return s;
}

ViewQuestion question(FeedingSimulator& world, const PlanChoices& shown, const world::ArmConfig& conf) {
  ViewQuestion q;
  q.conf = conf;
  q.state = biteViewState(world, shown, conf);
  world::Workspace& ws = world.world().workspace();
  const world::WorldState keep = ws.state();
  ws.setState(q.state);
  q.occlusion = world.occlusionAt(conf);
  ws.setState(keep);
  return q;
}

}  // namespace

StudySession::StudySession(const approach::PreparedProgram& lp, const ProgramFacts& facts, const StudyOptions& options,
                           int participant)
    : lp_(lp),
      participant_(participant),
      seed_(participantSeed(options.seed, participant)),
      arms_(makeStudyArms(lp, facts, options, participant)) {}

const MealPresentation& StudySession::current() {
  if (finished()) throw std::logic_error("the study is over: every meal was answered");
  if (current_) return *current_;
  MealPresentation p;
  p.meal = meal_;
  for (StudyArm& arm : arms_) p.offers.emplace(arm.approach, offerMeal(lp_, arm, meal_, tally_));
  rt::Rng coin(approach::deriveSeed(seed_, 9000 + meal_));
  const auto& names = studyApproaches();
  p.options =
      coin.coin() ? std::array<std::string, 2>{names[0], names[1]} : std::array<std::string, 2>{names[1], names[0]};
  StudyArm& cbtl = arms_.front();
  const MealOffer& offer = p.offers.at(cbtl.approach);
  if (offer.shown.ok && offer.read.abovePlateConf)
    p.views.push_back(question(*cbtl.world, offer.read, *offer.read.abovePlateConf));
  if (offer.exploringConf) p.views.push_back(question(*cbtl.world, offer.read, *offer.exploringConf));
  current_ = std::move(p);
  return *current_;
}

std::optional<std::string> StudySession::check(const ParticipantAnswers& answers) {
  const MealPresentation& p = current();
  if (answers.blocked.size() != p.views.size())
    return fmt::format("{} view answers for {} view questions", answers.blocked.size(), p.views.size());
  for (const auto& [name, offer] : p.offers) {
    if (!offer.shown.ok) continue;
    const Meal& meal = paperMeals().at(meal_);
    if (auto problem = checkIdeals(
            BiteOffer{meal.food, meal.dips, offer.read.dip, offer.read.signal, offer.read.verbosity}, answers.ideals))
      return problem;
  }
  return std::nullopt;
}

std::map<std::string, MealChoice> StudySession::answer(const ParticipantAnswers& answers) {
  if (auto problem = check(answers)) throw std::invalid_argument(*problem);
  const MealPresentation& p = current();
  MealAnswers said;
  said.ideals = answers.ideals;
  for (std::size_t i = 0; i < p.views.size(); ++i) said.views.emplace_back(p.views[i].conf, answers.blocked[i]);
  std::map<std::string, MealChoice> judged;
  for (StudyArm& arm : arms_) {
    // Only CBTL's configurations were shown; No Personalization's choice is judged on the bite's answers alone.
    MealAnswers forArm = said;
    if (!arm.learns) forArm.views.clear();
    MealChoice choice = answerMeal(lp_, arm, p.offers.at(arm.approach), forArm);
    if (!arm.learns) {
      choice.preferences.erase("view");  // never asked about: unknown, not met
      choice.preferences.erase("bite");
    }
    judged.emplace(arm.approach, std::move(choice));
  }
  current_.reset();
  ++meal_;
  return judged;
}

}  // namespace cbtl::domains::feeding
