// The simulated web study and the demonstration (domains/feeding/FeedingStudy.h, FeedingDemo.h): the paper's five
// meals, both approaches judged on every meal, CBTL learning between meals, results per participant independent of
// the others, and the demonstration's decisions judged against the participant's hidden occlusion threshold.
#include "domains/feeding/FeedingDemo.h"
#include "domains/feeding/FeedingStudy.h"

#include "app/DomainSolverOptions.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

namespace {

using namespace cbtl::domains::feeding;

const cbtl::app::LoadedProgram& feedingProgram() {
  static const auto lp = cbtl::app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  return *lp;
}

StudyOptions studyOptions(int first, int participants) {
  StudyOptions o;
  o.firstParticipant = first;
  o.participants = participants;
  o.solver = cbtl::app::domainSolverOptions("feeding");
  return o;
}

TEST(FeedingStudy, ThePaperMealsAreTheStudysFiveInOrder) {
  const auto& m = paperMeals();
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0], (Meal{"french fries", {"bbqSauce", "ketchup"}, "alone", "rectangular"}));
  EXPECT_EQ(m[1], (Meal{"raw vegetables", {"hummus", "ranch"}, "withFriend", "circular"}));
  EXPECT_EQ(m[2], (Meal{"potato wedges", {"bbqSauce", "ketchup"}, "withTv", "circular"}));
  EXPECT_EQ(m[3], (Meal{"carrot sticks", {"hummus", "ranch"}, "alone", "circular"}));
  EXPECT_EQ(m[4], (Meal{"tater tots", {"bbqSauce", "ketchup"}, "withFriendAndTv", "rectangular"}));
}

TEST(FeedingStudy, CbtlLearnsFromTheAnswersAndNoPersonalizationDoesNot) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  const StudyResult r = runStudy(lp, cbtl::test::programFacts("feeding"), studyOptions(0, 4));
  ASSERT_EQ(r.participants.size(), 4u);
  ASSERT_EQ(r.meals.size(), 5u);
  EXPECT_EQ(r.recheckViolations, 0);
  int cbtlLater = 0, npLater = 0;
  for (const auto& p : r.participants) {
    ASSERT_EQ(p.meals.size(), 5u);
    // Meal 1: nothing learned yet, the same start and the same solver seed: the same choices.
    const MealChoice& c1 = p.meals[0].at("cbtl");
    const MealChoice& n1 = p.meals[0].at("no-personalization");
    EXPECT_TRUE(c1.solved && n1.solved) << p.participant;
    EXPECT_EQ(c1.dip, n1.dip);
    EXPECT_EQ(c1.signal, n1.signal);
    EXPECT_EQ(c1.verbosity, n1.verbosity);
    for (std::size_t k = 1; k < 5; ++k) {
      for (const char* pref : {"signal", "verbosity"}) {
        cbtlLater += p.meals[k].at("cbtl").preferences.at(pref) ? 1 : 0;
        npLater += p.meals[k].at("no-personalization").preferences.at(pref) ? 1 : 0;
      }
    }
  }
  // 4 participants x meals 2-5 x (signal, verbosity) = 32 judgements each. Meal 5's setting (a friend and the
  // TV) is new, and some participants change signal or verbosity in it.
  EXPECT_GE(cbtlLater, 22) << "No Personalization: " << npLater;
  EXPECT_LT(npLater, cbtlLater - 8);
  // The dip with the potato foods of meals 3 and 5, after the fries of meal 1 (FeedingUser::participant: a
  // participant mostly takes the same dip with foods of one kind): 4 participants x 2 meals.
  int cbtlDip = 0, npDip = 0;
  for (const auto& p : r.participants)
    for (std::size_t k : {2u, 4u}) {
      cbtlDip += p.meals[k].at("cbtl").preferences.at("dip") ? 1 : 0;
      npDip += p.meals[k].at("no-personalization").preferences.at("dip") ? 1 : 0;
    }
  EXPECT_GT(cbtlDip, npDip) << "CBTL " << cbtlDip << ", No Personalization " << npDip;
  int judged = 0;
  for (const auto& m : r.meals) judged += m.cbtlBetter + m.tied + m.cbtlWorse;
  EXPECT_EQ(judged, 20);
  EXPECT_NE(studyCsv(r).find("3,5,no-personalization,1,"), std::string::npos) << studyCsv(r);
}

TEST(FeedingStudy, AParticipantsResultsDoNotDependOnTheOthers) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  const auto& facts = cbtl::test::programFacts("feeding");
  const StudyResult two = runStudy(lp, facts, studyOptions(0, 2));
  const StudyResult alone = runStudy(lp, facts, studyOptions(1, 1));
  ASSERT_EQ(alone.participants.size(), 1u);
  for (std::size_t k = 0; k < 5; ++k) {
    for (const auto& name : studyApproaches()) {
      const MealChoice& a = two.participants[1].meals[k].at(name);
      const MealChoice& b = alone.participants[0].meals[k].at(name);
      EXPECT_EQ(a.dip, b.dip) << k << name;
      EXPECT_EQ(a.signal, b.signal) << k << name;
      EXPECT_EQ(a.verbosity, b.verbosity) << k << name;
      EXPECT_EQ(a.occlusion, b.occlusion) << k << name;
      EXPECT_EQ(a.preferences, b.preferences) << k << name;
    }
  }
}

// A participant's typed answers (the web study's path, answerMeal): what they say is what CBTL learns, and what it
// offers next follows it; No Personalization offers the same whatever they say.
TEST(FeedingStudy, AnsweredMealsTeachCbtlWhatTheParticipantSaid) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  StudyResult tally;
  std::vector<StudyArm> arms = makeStudyArms(lp, cbtl::test::programFacts("feeding"), studyOptions(0, 1), 7);
  StudyArm& cbtlArm = arms.at(0);
  StudyArm& npArm = arms.at(1);
  ASSERT_EQ(cbtlArm.approach, "cbtl");
  // The participant wants no dip with any potato, the button and silence; the first three meals teach it.
  // Meal 1: the exploring CSP's configuration is called blocked, meal 2 the shown choice's, meal 3 neither.
  const auto answer = [](const MealOffer& offer, std::size_t k) {
    MealAnswers a;
    a.ideals = BiteIdeals{"noDip", "button", "silent"};
    if (offer.read.abovePlateConf) a.views.emplace_back(*offer.read.abovePlateConf, k == 1);
    if (offer.exploringConf) a.views.emplace_back(*offer.exploringConf, k == 0);
    return a;
  };
  std::size_t labels = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const MealOffer c = offerMeal(lp, cbtlArm, k, tally);
    const MealOffer n = offerMeal(lp, npArm, k, tally);
    ASSERT_TRUE(c.shown.ok && n.shown.ok) << k;
    EXPECT_TRUE(c.exploringConf.has_value()) << "a learner asks about its most uncertain view";
    EXPECT_FALSE(n.exploringConf.has_value());
    const MealChoice judged = answerMeal(lp, cbtlArm, c, answer(c, k));
    answerMeal(lp, npArm, n, answer(n, k));
    EXPECT_TRUE(judged.solved) << k;
    EXPECT_EQ(judged.preferences.at("dip"), c.read.dip == "noDip");
    EXPECT_EQ(judged.preferences.at("view"), k != 1) << "only the shown choice's picture judges its view";
    // Every answer is learned: the three questions account for every choice, and each view is one more label.
    EXPECT_GT(cbtlArm.model.dataCount(), labels) << k;
    labels = cbtlArm.model.dataCount();
  }
  EXPECT_EQ(npArm.model.dataCount(), 0u);
  // Meal 5 (tater tots, with a friend and the TV): the potato dip was taught three times over.
  const MealOffer c5 = offerMeal(lp, cbtlArm, 4, tally);
  ASSERT_TRUE(c5.shown.ok);
  EXPECT_EQ(c5.read.dip, "noDip");
  // Meal 4 (alone, like meal 1): signal and verbosity as taught; without learning, something else.
  const MealOffer c4 = offerMeal(lp, cbtlArm, 3, tally);
  const MealOffer n4 = offerMeal(lp, npArm, 3, tally);
  ASSERT_TRUE(c4.shown.ok && n4.shown.ok);
  EXPECT_EQ(c4.read.signal, "button");
  EXPECT_EQ(c4.read.verbosity, "silent");
  EXPECT_FALSE(n4.read.signal == "button" && n4.read.verbosity == "silent" && n4.read.dip == "noDip")
      << "the untrained robot happens to make the taught choices: the test would show nothing";
  EXPECT_EQ(tally.recheckViolations, 0);
}

TEST(FeedingStudy, AnswersOutsideTheMealsChoicesAreRefusedAndTeachNothing) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  StudyResult tally;
  std::vector<StudyArm> arms = makeStudyArms(lp, cbtl::test::programFacts("feeding"), studyOptions(0, 1), 3);
  const MealOffer offer = offerMeal(lp, arms.at(0), 0, tally);
  ASSERT_TRUE(offer.shown.ok);
  MealAnswers bad;
  bad.ideals = BiteIdeals{"ranch", "button", "silent"};  // meal 1 serves ketchup and BBQ sauce
  EXPECT_THROW(answerMeal(lp, arms.at(0), offer, bad), std::invalid_argument);
  EXPECT_EQ(arms.at(0).model.dataCount(), 0u);
}

TEST(FeedingDemo, ComplaintsFollowTheHiddenThresholdAndCbtlKeepsTheViewClear) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  DemoOptions o;
  o.trials = 2;
  o.study = studyOptions(0, 1);
  int observed = 0;
  const DemoResult r = runDemo(lp, cbtl::test::programFacts("feeding"), o,
                               [&](int, const std::string&, const DemoStep&, FeedingSimulator&) { ++observed; });
  EXPECT_EQ(r.meal, paperMeals()[4]);
  ASSERT_EQ(r.trials.size(), 2u);
  EXPECT_EQ(observed, 2 * 2 * 4);
  int unchanged = 0, kept = 0;
  for (const auto& trial : r.trials) {
    for (const auto& name : studyApproaches()) {
      const auto& steps = trial.steps.at(name);
      ASSERT_EQ(steps.size(), 4u);
      EXPECT_EQ(steps[0].task, "feedBite");
      EXPECT_EQ(steps[2].task, "prepareDrink");
      EXPECT_EQ(steps[3].task, "giveDrink");
      // The meal starts with the plate where the caregiver put it, in front of the user.
      EXPECT_NEAR(steps[0].plateFrom.at(1), o.plateY, 1e-9);
      for (const auto& s : steps) {
        EXPECT_TRUE(s.solved) << name << " " << s.request;
        if (!s.conf) continue;
        // The user complains at each move to the configuration exactly when its score reaches their threshold.
        EXPECT_EQ(s.complaints > 0, s.occlusion >= r.threshold) << name << " " << s.request << " " << s.occlusion;
        if (name == "cbtl") {
          EXPECT_EQ(s.complaints, 0) << s.request << " " << s.occlusion;
        }
      }
      // Nothing changed between the two bites and the first was judged clear: the plate may stay exactly where it
      // is (the search draws that spot, keepOrUniformInBox). Not always within Feeding's 100 improvement attempts:
      // each redraws one variable and its dependents, and the configuration above the kept plate must pass too.
      if (steps[0].complaints == 0) {
        ++unchanged;
        kept += steps[1].plateTo == steps[1].plateFrom ? 1 : 0;
      }
    }
  }
  // Held up at its post-grasp configuration the drink is in the view: without learning, where the caregiver put it
  // (0.32, 0.67), it blocks the view. (In one of the two trials No Personalization draws another spot for the drink,
  // low in y, where the held drink is out of view; which trial depends on its draws.)
  int blocked = 0;
  for (const auto& trial : r.trials) blocked += trial.steps.at("no-personalization")[3].complaints > 0 ? 1 : 0;
  EXPECT_GT(blocked, 0);
  EXPECT_GT(unchanged, 0);
  EXPECT_GT(kept, 0) << "none of " << unchanged << " second bites kept the plate where it was";
}

}  // namespace
