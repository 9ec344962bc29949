// One web-study participant, meal by meal (domains/feeding/StudySession.h): both approaches shown in a drawn
// order, CBTL's view questions with the scene to render, answers checked before anything changes, and a session
// rebuilt from the same answers showing exactly what the first showed (a restarted server).
#include "domains/feeding/StudySession.h"

#include "app/DomainSolverOptions.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace {

using namespace cbtl::domains::feeding;

const cbtl::app::LoadedProgram& feedingProgram() {
  static const auto lp = cbtl::app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  return *lp;
}

StudyOptions options() {
  StudyOptions o;
  o.solver = cbtl::app::domainSolverOptions("feeding");
  return o;
}

ParticipantAnswers answersFor(const MealPresentation& p, std::size_t meal) {
  ParticipantAnswers a;
  a.ideals = BiteIdeals{"noDip", meal % 2 == 0 ? "button" : "mouthOpen", "silent"};
  for (std::size_t i = 0; i < p.views.size(); ++i) a.blocked.push_back(p.views[i].occlusion >= 0.04);
  return a;
}

}  // namespace

TEST(StudySession, ShowsBothApproachesAndCbtlsViewsThenFinishesAfterFiveMeals) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  StudySession session(lp, cbtl::test::programFacts("feeding"), options(), 2);
  for (std::size_t k = 0; k < paperMeals().size(); ++k) {
    ASSERT_FALSE(session.finished());
    EXPECT_EQ(session.meal(), k);
    const MealPresentation& p = session.current();
    EXPECT_EQ(p.meal, k);
    EXPECT_EQ(std::set<std::string>(p.options.begin(), p.options.end()),
              std::set<std::string>(studyApproaches().begin(), studyApproaches().end()));
    ASSERT_EQ(p.offers.size(), 2u);
    const MealOffer& cbtl = p.offers.at("cbtl");
    ASSERT_TRUE(cbtl.shown.ok) << k;
    ASSERT_EQ(p.views.size(), 2u) << "the shown configuration and the most uncertain one";
    EXPECT_EQ(p.views[0].conf, *cbtl.read.abovePlateConf);
    for (const ViewQuestion& v : p.views) {
      EXPECT_EQ(v.state.arm, v.conf);
      ASSERT_TRUE(v.state.held.has_value());
      EXPECT_EQ(v.state.held->object, "utensil");
      ASSERT_TRUE(cbtl.read.plate.has_value());
      EXPECT_DOUBLE_EQ(v.state.objects.at("plate").position.x(), (*cbtl.read.plate)[0]);
      EXPECT_DOUBLE_EQ(v.state.objects.at("plate").position.y(), (*cbtl.read.plate)[1]);
      EXPECT_GE(v.occlusion, 0.0);
    }
    // Refused answers change nothing: the same meal, the same presentation.
    ParticipantAnswers wrongCount = answersFor(p, k);
    wrongCount.blocked.push_back(false);
    EXPECT_THROW(session.answer(wrongCount), std::invalid_argument);
    ParticipantAnswers wrongDip = answersFor(p, k);
    wrongDip.ideals.dip = "mustard";
    EXPECT_THROW(session.answer(wrongDip), std::invalid_argument);
    EXPECT_EQ(session.meal(), k);
    const auto judged = session.answer(answersFor(session.current(), k));
    EXPECT_TRUE(judged.at("cbtl").preferences.count("view"));
    EXPECT_FALSE(judged.at("no-personalization").preferences.count("view")) << "its views were never shown";
  }
  EXPECT_TRUE(session.finished());
  EXPECT_THROW(session.current(), std::logic_error);
  EXPECT_THROW(session.answer(ParticipantAnswers{}), std::logic_error);
  EXPECT_EQ(session.tally().recheckViolations, 0);
}

TEST(StudySession, ASessionRebuiltFromTheSameAnswersShowsTheSameMeal) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  const auto& facts = cbtl::test::programFacts("feeding");
  StudySession first(lp, facts, options(), 5);
  std::vector<ParticipantAnswers> given;
  for (std::size_t k = 0; k < 2; ++k) {
    given.push_back(answersFor(first.current(), k));
    first.answer(given.back());
  }
  StudySession rebuilt(lp, facts, options(), 5);
  for (const auto& a : given) {
    rebuilt.current();
    rebuilt.answer(a);
  }
  const MealPresentation& x = first.current();
  const MealPresentation& y = rebuilt.current();
  EXPECT_EQ(x.meal, 2u);
  EXPECT_EQ(x.options, y.options);
  for (const auto& name : studyApproaches()) {
    const PlanChoices& a = x.offers.at(name).read;
    const PlanChoices& b = y.offers.at(name).read;
    EXPECT_EQ(a.dip, b.dip) << name;
    EXPECT_EQ(a.signal, b.signal) << name;
    EXPECT_EQ(a.verbosity, b.verbosity) << name;
    EXPECT_EQ(a.plate, b.plate) << name;
    EXPECT_EQ(a.abovePlateConf, b.abovePlateConf) << name;
  }
  ASSERT_EQ(x.views.size(), y.views.size());
  for (std::size_t i = 0; i < x.views.size(); ++i) {
    EXPECT_EQ(x.views[i].conf, y.views[i].conf);
    EXPECT_EQ(x.views[i].occlusion, y.views[i].occlusion);
  }
}

TEST(StudySession, TheOptionOrderIsDrawnPerMeal) {
  const auto& lp = feedingProgram();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  std::set<std::string> firstShown;
  for (int participant = 0; participant < 4; ++participant) {
    StudySession session(lp, cbtl::test::programFacts("feeding"), options(), participant);
    firstShown.insert(session.current().options[0]);
  }
  EXPECT_EQ(firstShown.size(), 2u) << "over four participants' first meals, each approach is Option A at least once";
}
