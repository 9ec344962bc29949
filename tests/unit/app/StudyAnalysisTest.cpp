// StudyAnalysisTest.cpp — the web study's analysis (app/study/StudyAnalysis.h) over a hand-written database whose
// records follow docs/study-api.md's "Requests and what is stored"; every expected number is worked out by hand in
// the comment next to it.
//
// The study below: five participants. P1, P2, P3 complete every page; P4 stops after meal 2's rating (so meal 1's
// answers and meal 2's rating count, but no path); P5 begins and records nothing. Times are a formula of the
// participant's position i (0-based) and the trial t: rt_ms = 1000 (t + 1) + 500 i, elapsed_ms = 60000 (t + 1) +
// 10000 i.
#include "app/study/StudyAnalysis.h"

#include "app/study/SignedRank.h"
#include "app/study/StudyRecords.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace cbtl::app::study {
namespace {

struct Answer {
  std::string dip, signal, verbosity;
};

struct Offer {
  bool solved = true;
  Answer choice;
};

std::string offerJson(const Offer& o) {
  if (!o.solved) return R"({"solved": false})";
  return R"({"solved": true, "dip": ")" + o.choice.dip + R"(", "signal": ")" + o.choice.signal +
         R"(", "verbosity": ")" + o.choice.verbosity + R"("})";
}

std::string demographicsJson(const std::string& age, const std::string& gender, bool robot, bool fed) {
  return R"({"age": )" + age + R"(, "gender": ")" + gender + R"(", "gender_other": "", "robot_experience": )" +
         (robot ? "true" : "false") + R"(, "fed_experience": )" + (fed ? "true" : "false") + "}";
}

// A stored rating: the page's likert answer and, as the server stores it, the same answer on CBTL's scale and the two
// options in the order shown (CBTL as option B or A).
std::string ratingJson(int cbtlPreference, bool cbtlIsOptionB) {
  const int likert = cbtlIsOptionB ? cbtlPreference : 6 - cbtlPreference;
  const std::string np = R"({"approach": "no-personalization", "solved": true, "dip": "noDip", "signal": )"
                         R"("mouthOpen", "verbosity": "chatty"})";
  const std::string cbtl = R"({"approach": "cbtl", "solved": true, "dip": "ketchup", "signal": "button", )"
                           R"("verbosity": "silent"})";
  return R"({"likert": )" + std::to_string(likert) + R"(, "cbtl_preference": )" + std::to_string(cbtlPreference) +
         R"(, "meal_description": "a meal as the server describes it", "options": [)" +
         (cbtlIsOptionB ? np + ", " + cbtl : cbtl + ", " + np) + "]}";
}

std::string answersJson(const Answer& a, const std::vector<bool>& blocked, const Offer& cbtl, const Offer& np,
                        const std::string& metCbtl, const std::string& metNp) {
  std::string blockedJson, views;
  for (std::size_t k = 0; k < blocked.size(); ++k) {
    blockedJson += std::string(k ? ", " : "") + (blocked[k] ? "true" : "false");
    views +=
        std::string(k ? ", " : "") + R"({"occlusion": 0.031, "shown_choice": )" + (k == 0 ? "true" : "false") + "}";
  }
  return R"({"dip": ")" + a.dip + R"(", "signal": ")" + a.signal + R"(", "verbosity": ")" + a.verbosity +
         R"(", "blocked": [)" + blockedJson + R"(], "predicted": {"cbtl": )" + offerJson(cbtl) +
         R"(, "no-personalization": )" + offerJson(np) + R"(}, "views": [)" + views + R"(], "met": {"cbtl": )" +
         metCbtl + R"(, "no-personalization": )" + metNp + "}}";
}

std::string met(bool dip, bool signal, bool verbosity) {
  auto b = [](bool v) { return v ? std::string("true") : std::string("false"); };
  return R"({"dip": )" + b(dip) + R"(, "signal": )" + b(signal) + R"(, "verbosity": )" + b(verbosity) + "}";
}

std::string metWithView(bool dip, bool signal, bool verbosity, bool view) {
  std::string m = met(dip, signal, verbosity);
  return m.substr(0, m.size() - 1) + R"(, "view": )" + (view ? "true" : "false") + "}";
}

// Meals 2..5 of every participant: CBTL offered exactly the answer and met everything; No Personalization offered
// noDip, mouthOpen, chatty, and met dip and signal only; one picture, not blocked.
std::string plainAnswersJson(const Answer& a) {
  return answersJson(a, {false}, {true, a}, {true, {"noDip", "mouthOpen", "chatty"}},
                     metWithView(true, true, true, true), met(true, true, false));
}

class StudyAnalysisTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("cbtl-study-analysis-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "study.sqlite").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Begins participant number `i` (0-based) and stores `responses` as their pages 0, 1, 2, ... (kind and meal as the
  // API's fixed page sequence says); completes them after the `complete` page.
  static void addParticipant(StudyRecords& study, int i, const std::string& id,
                             const std::vector<std::string>& responses) {
    study.begin(id, static_cast<std::uint64_t>(i), "{}");
    for (std::size_t t = 0; t < responses.size(); ++t) {
      const auto trial = static_cast<std::int64_t>(t);
      std::string kind = trial == 0 ? "consent" : trial == 1 ? "demographics" : trial == 12 ? "complete" : "";
      if (kind.empty()) kind = trial % 2 == 0 ? "rating" : "answers";
      const int meal = trial >= 2 && trial < 12 ? static_cast<int>((trial - 2) / 2) + 1 : 0;
      study.record(
          {id, trial, kind, meal, 60000 * (trial + 1) + 10000 * i, 1000 * (trial + 1) + 500 * i, responses[t]});
    }
    if (responses.size() == 13) study.complete(id);
  }

  // A whole participant: their five meals' preferences and answers; meal 1's answers page is `meal1Answers`.
  static std::vector<std::string> wholeStudy(const std::string& demographics, const std::vector<int>& preferences,
                                             bool cbtlIsOptionB, const std::string& meal1Answers,
                                             const std::vector<Answer>& meals2to5) {
    std::vector<std::string> pages{R"({"agree": true})", demographics};
    for (int meal = 1; meal <= kMeals; ++meal) {
      pages.push_back(ratingJson(preferences[static_cast<std::size_t>(meal - 1)], cbtlIsOptionB));
      pages.push_back(meal == 1 ? meal1Answers : plainAnswersJson(meals2to5[static_cast<std::size_t>(meal - 2)]));
    }
    pages.push_back(R"({"comments": "the robot was slow, but fine"})");
    return pages;
  }

  // The study of the top of this file.
  void fillStudy() {
    StudyRecords study(path_);
    const Offer np1{true, {"ketchup", "mouthOpen", "chatty"}};
    addParticipant(study, 0, "P1",
                   wholeStudy(demographicsJson("19", "female", true, false), {5, 4, 4, 5, 4}, true,
                              answersJson({"ketchup", "mouthOpen", "silent"}, {false, true},
                                          {true, {"ketchup", "mouthOpen", "silent"}}, np1,
                                          metWithView(true, true, true, true), met(true, true, false)),
                              {{"ranch", "mouthOpen", "silent"},
                               {"ketchup", "mouthOpen", "brief"},
                               {"ranch", "mouthOpen", "silent"},
                               {"ketchup", "mouthOpen", "silent"}}));
    addParticipant(
        study, 1, "P2",
        wholeStudy(demographicsJson("null", "male", false, false), {4, 2, 5, 4, 3}, false,
                   answersJson({"noDip", "button", "chatty"}, {false, false}, {true, {"ketchup", "button", "silent"}},
                               np1, metWithView(true, false, false, false), met(false, false, true)),
                   {{"noDip", "button", "chatty"},
                    {"noDip", "button", "chatty"},
                    {"noDip", "button", "chatty"},
                    {"noDip", "button", "chatty"}}));
    addParticipant(study, 2, "P3",
                   wholeStudy(demographicsJson("45", "non-binary", false, true), {3, 4, 5, 5, 4}, true,
                              answersJson({"ketchup", "mouthOpen", "silent"}, {true}, {false, {}}, np1,
                                          metWithView(false, false, false, true), met(true, true, false)),
                              {{"ranch", "mouthOpen", "silent"},
                               {"ketchup", "mouthOpen", "brief"},
                               {"ranch", "mouthOpen", "silent"},
                               {"ketchup", "button", "silent"}}));
    // P4's met.cbtl has no view, so meal 1's view share is over three records.
    addParticipant(study, 3, "P4",
                   {R"({"agree": true})", demographicsJson("30", "male", true, false), ratingJson(5, false),
                    answersJson({"bbqSauce", "autoContinue", "brief"}, {false, false, false},
                                {true, {"bbqSauce", "autoContinue", "chatty"}}, np1, met(true, true, false),
                                met(false, false, false)),
                    ratingJson(4, true)});
    study.begin("P5", 4, "{}");
  }

  StudyAnalysis analyzed() {
    fillStudy();
    return analyzeStudy(StudyRecords(path_, /*create=*/false));
  }

  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(StudyAnalysisTest, CountsParticipantsAndSummarizesDemographics) {
  const StudyAnalysis a = analyzed();
  EXPECT_EQ(a.participants.begun, 5u);
  EXPECT_EQ(a.participants.consented, 4u);  // P5 has no consent
  EXPECT_EQ(a.participants.completed, 3u);  // P4 stopped
  const Demographics& d = a.demographics;
  EXPECT_EQ(d.answered, 4u);
  EXPECT_EQ(d.agesGiven, 3u);  // P2 did not say
  EXPECT_EQ(d.ageMin, 19);
  EXPECT_EQ(d.ageMax, 45);
  ASSERT_TRUE(d.ageMean);
  EXPECT_DOUBLE_EQ(*d.ageMean, (19.0 + 45 + 30) / 3);
  const std::map<std::string, std::size_t> genders{
      {"male", 2}, {"female", 1}, {"non-binary", 1}, {"prefer-not-to-say", 0}, {"other", 0}};
  EXPECT_EQ(d.genders, genders);
  EXPECT_EQ(d.robotExperience.hits, 2u);  // P1, P4
  EXPECT_EQ(d.robotExperience.total, 4u);
  EXPECT_EQ(d.fedExperience.hits, 1u);  // P3
  EXPECT_EQ(d.fedExperience.total, 4u);
}

TEST_F(StudyAnalysisTest, RatingsPerMealAreMeanSampleSdAndTheSignedRankTestAgainstNeutral) {
  const StudyAnalysis a = analyzed();
  ASSERT_EQ(a.ratings.size(), 5u);
  // cbtl_preference per meal, participants in creation order (P4 rated meals 1 and 2).
  const std::vector<std::vector<double>> values{{5, 4, 3, 5}, {4, 2, 4, 4}, {4, 5, 5}, {5, 4, 5}, {4, 3, 4}};
  // mean; sd: sqrt(sum of squared deviations / (n - 1)).
  const std::vector<double> means{4.25, 3.5, 14.0 / 3, 14.0 / 3, 11.0 / 3};
  const std::vector<double> sds{std::sqrt(2.75 / 3), 1.0, std::sqrt(1.0 / 3), std::sqrt(1.0 / 3), std::sqrt(1.0 / 3)};
  for (std::size_t m = 0; m < 5; ++m) {
    const MealRatings& r = a.ratings[m];
    EXPECT_EQ(r.meal, static_cast<int>(m) + 1);
    EXPECT_EQ(r.cbtlPreferences, values[m]) << "meal " << m + 1;
    ASSERT_TRUE(r.mean && r.sd);
    EXPECT_NEAR(*r.mean, means[m], 1e-12);
    EXPECT_NEAR(*r.sd, sds[m], 1e-12);
    const SignedRankResult direct = signedRank(values[m], 3.0);
    EXPECT_EQ(r.test.n, direct.n);
    EXPECT_EQ(r.test.zeros, direct.zeros);
    EXPECT_EQ(r.test.method, direct.method);
    EXPECT_DOUBLE_EQ(r.test.wPlus, direct.wPlus);
    EXPECT_DOUBLE_EQ(r.test.z, direct.z);
    EXPECT_DOUBLE_EQ(r.test.pTwoSided, direct.pTwoSided);
    EXPECT_DOUBLE_EQ(r.test.pGreater, direct.pGreater);
    EXPECT_DOUBLE_EQ(r.test.effectSize, direct.effectSize);
  }
  // Meal 1 by hand: d = 2, 1, 0, 2; the zero dropped; |d| ranks 1 -> 1, 2 and 2 -> 2.5 each; all positive: W+ = 6.
  EXPECT_EQ(a.ratings[0].test.n, 3u);
  EXPECT_EQ(a.ratings[0].test.zeros, 1u);
  EXPECT_DOUBLE_EQ(a.ratings[0].test.wPlus, 6.0);
  EXPECT_EQ(a.ratings[0].test.method, SignedRankResult::Method::Normal);  // tied ranks
}

TEST_F(StudyAnalysisTest, PredictionAccuracyMetAndPicturesPerMeal) {
  const StudyAnalysis a = analyzed();
  ASSERT_EQ(a.accuracy.size(), 5u);
  const MealAccuracy& m1 = a.accuracy[0];
  EXPECT_EQ(m1.answers, 4u);
  auto expectShare = [](const Share& s, std::size_t hits, std::size_t total, const std::string& what) {
    EXPECT_EQ(s.hits, hits) << what;
    EXPECT_EQ(s.total, total) << what;
  };
  // Answers: P1 ketchup mouthOpen silent; P2 noDip button chatty; P3 ketchup mouthOpen silent; P4 bbqSauce
  // autoContinue brief. CBTL offered: P1 all three right; P2 ketchup button silent (signal right); P3 unsolved (all
  // wrong); P4 bbqSauce autoContinue chatty (dip and signal right).
  expectShare(m1.predicted.at("cbtl").at("dip"), 2, 4, "cbtl dip");
  expectShare(m1.predicted.at("cbtl").at("signal"), 3, 4, "cbtl signal");
  expectShare(m1.predicted.at("cbtl").at("verbosity"), 1, 4, "cbtl verbosity");
  // No Personalization offered ketchup mouthOpen chatty to all: dip P1 P3, signal P1 P3, verbosity P2.
  expectShare(m1.predicted.at("no-personalization").at("dip"), 2, 4, "np dip");
  expectShare(m1.predicted.at("no-personalization").at("signal"), 2, 4, "np signal");
  expectShare(m1.predicted.at("no-personalization").at("verbosity"), 1, 4, "np verbosity");
  ASSERT_TRUE(m1.predicted.at("cbtl").at("signal").share());
  EXPECT_DOUBLE_EQ(*m1.predicted.at("cbtl").at("signal").share(), 0.75);
  // met.cbtl: P1 ttt view t; P2 tff view f; P3 fff view t; P4 ttf, no view.
  expectShare(m1.met.at("cbtl").at("dip"), 3, 4, "cbtl met dip");
  expectShare(m1.met.at("cbtl").at("signal"), 2, 4, "cbtl met signal");
  expectShare(m1.met.at("cbtl").at("verbosity"), 1, 4, "cbtl met verbosity");
  expectShare(m1.met.at("cbtl").at("view"), 2, 3, "cbtl met view");
  // met.no-personalization: P1 ttf; P2 fft; P3 ttf; P4 fff; never a view.
  expectShare(m1.met.at("no-personalization").at("dip"), 2, 4, "np met dip");
  expectShare(m1.met.at("no-personalization").at("signal"), 2, 4, "np met signal");
  expectShare(m1.met.at("no-personalization").at("verbosity"), 1, 4, "np met verbosity");
  expectShare(m1.met.at("no-personalization").at("view"), 0, 0, "np met view");
  EXPECT_FALSE(m1.met.at("no-personalization").at("view").share());
  // Pictures: P1 [f, t], P2 [f, f], P3 [t], P4 [f, f, f]: 6 of 8 not blocked.
  expectShare(m1.notBlocked, 6, 8, "not blocked");

  // Meal 2 (P1 ranch mouthOpen silent, P2 noDip button chatty, P3 ranch mouthOpen silent): CBTL offered the answers;
  // No Personalization noDip mouthOpen chatty: dip P2, signal P1 P3, verbosity P2.
  const MealAccuracy& m2 = a.accuracy[1];
  EXPECT_EQ(m2.answers, 3u);
  for (const char* q : {"dip", "signal", "verbosity"}) expectShare(m2.predicted.at("cbtl").at(q), 3, 3, q);
  expectShare(m2.predicted.at("no-personalization").at("dip"), 1, 3, "m2 np dip");
  expectShare(m2.predicted.at("no-personalization").at("signal"), 2, 3, "m2 np signal");
  expectShare(m2.predicted.at("no-personalization").at("verbosity"), 1, 3, "m2 np verbosity");
  expectShare(m2.met.at("cbtl").at("view"), 3, 3, "m2 cbtl view");
  expectShare(m2.notBlocked, 3, 3, "m2 not blocked");
}

TEST_F(StudyAnalysisTest, SankeyPathsAndFlowsOverParticipantsWhoAnsweredEveryMeal) {
  const StudyAnalysis a = analyzed();
  ASSERT_EQ(a.sankeys.size(), 3u);
  const Sankey& dip = a.sankeys[0];
  EXPECT_EQ(dip.question, "dip");
  ASSERT_EQ(dip.participants.size(), 3u);  // not P4
  EXPECT_EQ(dip.participants[0].first, "P1");
  EXPECT_EQ(dip.participants[0].second.text, "ketchup > ranch > ketchup > ranch > ketchup");
  EXPECT_EQ(dip.participants[1].second.answers, std::vector<std::string>(5, "noDip"));
  ASSERT_EQ(dip.paths.size(), 2u);
  EXPECT_EQ(dip.paths[0].text, "ketchup > ranch > ketchup > ranch > ketchup");  // P1 and P3
  EXPECT_EQ(dip.paths[0].count, 2u);
  EXPECT_EQ(dip.paths[1].text, "noDip > noDip > noDip > noDip > noDip");
  EXPECT_EQ(dip.paths[1].count, 1u);
  // Flows by meal, then answers as text.
  const std::vector<std::tuple<int, std::string, std::string, std::size_t>> dipFlows{
      {1, "ketchup", "ranch", 2}, {1, "noDip", "noDip", 1}, {2, "noDip", "noDip", 1}, {2, "ranch", "ketchup", 2},
      {3, "ketchup", "ranch", 2}, {3, "noDip", "noDip", 1}, {4, "noDip", "noDip", 1}, {4, "ranch", "ketchup", 2}};
  ASSERT_EQ(dip.flows.size(), dipFlows.size());
  for (std::size_t k = 0; k < dipFlows.size(); ++k) {
    const auto& [meal, from, to, n] = dipFlows[k];
    EXPECT_EQ(dip.flows[k].mealFrom, meal) << k;
    EXPECT_EQ(dip.flows[k].answerFrom, from) << k;
    EXPECT_EQ(dip.flows[k].answerTo, to) << k;
    EXPECT_EQ(dip.flows[k].count, n) << k;
  }
  // Signal: three paths once each, so by text ('b' < 'm', and P3's path leaves P1's at meal 5's 'b').
  const Sankey& signal = a.sankeys[1];
  ASSERT_EQ(signal.paths.size(), 3u);
  EXPECT_EQ(signal.paths[0].text, "button > button > button > button > button");
  EXPECT_EQ(signal.paths[1].text, "mouthOpen > mouthOpen > mouthOpen > mouthOpen > button");
  EXPECT_EQ(signal.paths[2].text, "mouthOpen > mouthOpen > mouthOpen > mouthOpen > mouthOpen");
  for (const auto& p : signal.paths) EXPECT_EQ(p.count, 1u);
  // Meals 1-3: button -> button once, mouthOpen -> mouthOpen twice; meal 4: P3 leaves mouthOpen for button.
  ASSERT_EQ(signal.flows.size(), 9u);
  EXPECT_EQ(signal.flows[1].answerFrom, "mouthOpen");
  EXPECT_EQ(signal.flows[1].count, 2u);
  EXPECT_EQ(signal.flows[6].mealFrom, 4);
  EXPECT_EQ(signal.flows[6].answerFrom, "button");
  EXPECT_EQ(signal.flows[7].answerFrom, "mouthOpen");
  EXPECT_EQ(signal.flows[7].answerTo, "button");
  EXPECT_EQ(signal.flows[7].count, 1u);
  EXPECT_EQ(signal.flows[8].answerTo, "mouthOpen");
  EXPECT_EQ(signal.flows[8].count, 1u);
  const Sankey& verbosity = a.sankeys[2];
  ASSERT_EQ(verbosity.paths.size(), 2u);
  EXPECT_EQ(verbosity.paths[0].text, "silent > silent > brief > silent > silent");
  EXPECT_EQ(verbosity.paths[0].count, 2u);
}

TEST_F(StudyAnalysisTest, TimesAreMediansAndNinetiethPercentilesOfTheBrowsersMilliseconds) {
  const StudyAnalysis a = analyzed();
  ASSERT_EQ(a.rtByKind.size(), 5u);
  auto expectTime = [](const TimeSummary& t, const std::string& measure, std::size_t n, double median, double p90) {
    EXPECT_EQ(t.measure, measure);
    EXPECT_EQ(t.n, n) << measure;
    ASSERT_TRUE(t.medianMs && t.p90Ms) << measure;
    EXPECT_DOUBLE_EQ(*t.medianMs, median) << measure;
    EXPECT_DOUBLE_EQ(*t.p90Ms, p90) << measure;
  };
  // consent (t = 0): 1000, 1500, 2000, 2500; median at 1.5; p90 at 2.7: 2000 + 0.7 * 500.
  expectTime(a.rtByKind[0], "consent", 4, 1750, 2350);
  // demographics (t = 1): 2000 .. 3500 by 500.
  expectTime(a.rtByKind[1], "demographics", 4, 2750, 3350);
  // rating: P1 3000, 5000, .., 11000; P2 3500, .., 11500; P3 4000, .., 12000; P4 4500, 6500. Sorted, 17 values:
  // 3000 3500 4000 4500 5000 5500 6000 6500 [7000] 7500 8000 9000 9500 10000 11000 11500 12000; p90 at 14.4.
  expectTime(a.rtByKind[2], "rating", 17, 7000, 11000 + 0.4 * 500);
  // answers: P1 4000, .., 12000; P2 4500, .., 12500; P3 5000, .., 13000; P4 5500. Sorted, 16 values:
  // 4000 4500 5000 5500 6000 6500 7000 8000 | 8500 9000 10000 10500 11000 12000 12500 13000; p90 at 13.5.
  expectTime(a.rtByKind[3], "answers", 16, 8250, 12250);
  expectTime(a.rtByKind[4], "complete", 3, 13500, 13500 + 0.8 * 500);
  // elapsed_ms of the complete page (t = 12): 780000, 790000, 800000.
  expectTime(a.totalDuration, "total", 3, 790000, 790000 + 0.8 * 10000);
}

TEST_F(StudyAnalysisTest, AnIncompleteParticipantCountsForTheMealsTheyAnswered) {
  {
    StudyRecords study(path_);
    addParticipant(
        study, 0, "only",
        {R"({"agree": true})", demographicsJson("null", "prefer-not-to-say", false, false), ratingJson(2, true),
         answersJson({"hummus", "button", "brief"}, {}, {true, {"hummus", "button", "silent"}}, {false, {}},
                     met(true, true, false), met(false, false, false))});
  }
  const StudyAnalysis a = analyzeStudy(StudyRecords(path_, false));
  EXPECT_EQ(a.participants.completed, 0u);
  EXPECT_EQ(a.ratings[0].cbtlPreferences, std::vector<double>{2});
  ASSERT_TRUE(a.ratings[0].mean);
  EXPECT_FALSE(a.ratings[0].sd);  // one value has no sample sd
  EXPECT_EQ(a.ratings[1].n(), 0u);
  EXPECT_FALSE(a.ratings[1].mean);
  EXPECT_FALSE(a.ratings[1].test.tested);
  EXPECT_EQ(a.accuracy[0].answers, 1u);
  EXPECT_EQ(a.accuracy[0].predicted.at("cbtl").at("verbosity").hits, 0u);
  EXPECT_EQ(a.accuracy[0].predicted.at("no-personalization").at("dip").hits, 0u);  // unsolved
  EXPECT_EQ(a.accuracy[0].notBlocked.total, 0u);                                   // no pictures
  EXPECT_EQ(a.accuracy[1].answers, 0u);
  EXPECT_TRUE(a.sankeys[0].paths.empty());
  EXPECT_TRUE(a.sankeys[0].flows.empty());
  EXPECT_EQ(a.totalDuration.n, 0u);
  EXPECT_FALSE(a.totalDuration.medianMs);
  std::ostringstream report;
  printStudyAnalysis(a, report);  // every missing number printed as "-", nothing thrown
  EXPECT_NE(report.str().find("none given"), std::string::npos) << report.str();
}

TEST_F(StudyAnalysisTest, TheReportShowsEveryTableWithFixedFormats) {
  std::ostringstream out;
  printStudyAnalysis(analyzed(), out);
  const std::string report = out.str();
  for (const std::string line : {
           "participants: 5 begun, 4 consented, 3 completed\n",
           "demographics (4 answered): age 19..45, mean 31.3 (3 of 4 gave it)\n",
           "  gender: male 2, female 1, non-binary 1, prefer-not-to-say 0, other 0\n",
           "meals:\n  1 a meal as the server describes it\n",
           // Meal 1: mean 4.25, sd 0.957; the W+ = 6 of the ratings test above.
           "   1 |   4 |               4.25 ± 0.96 |     6.0 |",
           "   1 |       4 | cbtl               | 0.50 |   0.75 |      0.25 |     0.75 |       0.50 |          0.25 |"
           "     0.67\n",
           "   1 |       4 | no-personalization | 0.50 |   0.50 |      0.25 |     0.50 |       0.50 |          0.25 |"
           "        -\n",
           "pictures answered not blocked: meal 1 0.75 (6 of 8); meal 2 1.00 (3 of 3);",
           "  dip: 2 distinct paths\n       2  ketchup > ranch > ketchup > ranch > ketchup\n",
           "  rating           7.0 s    11.2 s  (n 17)\n",
           "whole study (completed participants): median 13.2 min, 90th percentile 13.3 min (n 3)\n",
       })
    EXPECT_NE(report.find(line), std::string::npos) << "no line\n" << line << "\nin\n" << report;
}

// The message of the StudyError that analyzing `records` of participant "P9" throws, or a failure.
std::string analysisError(const std::vector<StoredRecord>& records) {
  Participant p9;
  p9.id = "P9";
  try {
    analyzeStudy({p9}, records);
  } catch (const StudyError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no StudyError";
  return "";
}

std::vector<StoredRecord> firstPages(const std::string& ratingResponse) {
  return {{"P9", 0, "consent", 0, 10, 10, R"({"agree":true})", ""},
          {"P9", 1, "demographics", 0, 20, 10, demographicsJson("33", "other", true, true), ""},
          {"P9", 2, "rating", 1, 30, 10, ratingResponse, ""}};
}

TEST_F(StudyAnalysisTest, MalformedRecordsAreClearErrorsNamingParticipantTrialAndField) {
  EXPECT_EQ(analysisError(firstPages(R"({"likert": 6, "cbtl_preference": 6, "options": []})")),
            "participant 'P9', trial 2 (rating, meal 1): likert is 6, not an integer 1..5");
  EXPECT_EQ(analysisError(firstPages(R"({"likert": 2})")),
            "participant 'P9', trial 2 (rating, meal 1): the response has no cbtl_preference");
  // CBTL shown as option B: likert 2 means CBTL preference 2, not 4.
  std::string swapped = ratingJson(2, true);
  swapped.replace(swapped.find("\"cbtl_preference\": 2"), 20, "\"cbtl_preference\": 4");
  EXPECT_EQ(analysisError(firstPages(swapped)),
            "participant 'P9', trial 2 (rating, meal 1): cbtl_preference is 4, but likert 2 with CBTL as option B "
            "means 2");
  EXPECT_EQ(analysisError(firstPages("[1, 2]")),
            "participant 'P9', trial 2 (rating, meal 1): the response [1,2] is not a JSON object");
  EXPECT_EQ(analysisError(firstPages("{\"likert\": ")),
            "participant 'P9', trial 2 (rating, meal 1): the response is not JSON: '{\"likert\": '");

  std::vector<StoredRecord> wrongMeal = firstPages(ratingJson(3, true));
  wrongMeal[2].meal = 2;
  EXPECT_EQ(analysisError(wrongMeal), "participant 'P9', trial 2 (rating, meal 2): expected the rating page of meal 1");
  std::vector<StoredRecord> gap = firstPages(ratingJson(3, true));
  gap.erase(gap.begin() + 1);
  EXPECT_EQ(analysisError(gap), "participant 'P9', trial 2: no record of trial 1 before it");

  std::vector<StoredRecord> badAnswers = firstPages(ratingJson(3, true));
  std::string answers =
      answersJson({"ketchup", "button", "brief"}, {false}, {true, {"ketchup", "button", "brief"}},
                  {true, {"ketchup", "button", "brief"}}, met(true, true, true), met(true, true, true));
  answers.replace(answers.find("\"signal\": \"button\""), 18, "\"signal\": 7");
  badAnswers.push_back({"P9", 3, "answers", 1, 40, 10, answers, ""});
  EXPECT_EQ(analysisError(badAnswers),
            "participant 'P9', trial 3 (answers, meal 1): signal is 7, not a non-empty string");
  badAnswers[3].response = R"({"dip": "ketchup", "signal": "button", "verbosity": "brief", "blocked": [false],)"
                           R"( "predicted": {"cbtl": {"solved": "yes"}}})";
  EXPECT_EQ(analysisError(badAnswers),
            "participant 'P9', trial 3 (answers, meal 1): predicted.cbtl.solved is \"yes\", not true or false");

  std::vector<StoredRecord> declined = firstPages(ratingJson(3, true));
  declined[0].response = R"({"agree": false})";
  EXPECT_EQ(analysisError(declined),
            "participant 'P9', trial 0 (consent, meal 0): agree is false, but declining records nothing");
  std::vector<StoredRecord> stranger = firstPages(ratingJson(3, true));
  stranger[1].participant = "P8";
  EXPECT_EQ(analysisError(stranger), "participant 'P8', trial 1: a record of no known participant");

  // Through a database, the message starts with its path.
  {
    StudyRecords study(path_);
    addParticipant(study, 0, "P9", {R"({"agree": true})", demographicsJson("17", "female", false, false)});
  }
  try {
    analyzeStudy(StudyRecords(path_, false));
    ADD_FAILURE() << "no StudyError";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              path_ + ": participant 'P9', trial 1 (demographics, meal 0): age is 17, not an integer 18..120");
  }
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream text;
  text << f.rdbuf();
  return text.str();
}

TEST_F(StudyAnalysisTest, CsvFilesOfASmallStudyHoldExactlyTheseLines) {
  {
    StudyRecords study(path_);
    // One participant, CBTL preference 5 at every meal, dip always hummus, the rest of plainAnswersJson.
    addParticipant(study, 0, "solo",
                   wholeStudy(demographicsJson("25", "female", false, false), {5, 5, 5, 5, 4}, false,
                              plainAnswersJson({"hummus", "button", "silent"}),
                              {{"hummus", "button", "silent"},
                               {"hummus", "button", "silent"},
                               {"hummus", "button", "silent"},
                               {"hummus", "mouthOpen", "silent"}}));
  }
  const std::string out = (dir_ / "csv").string();
  writeStudyAnalysisCsv(analyzeStudy(StudyRecords(path_, false)), out);
  // One positive difference: W+ = 1 of 1; exact p(W+ >= 1) = 1/2, two-sided 1; z = (1 - 0.5 - 0.5) / sd = 0.
  EXPECT_EQ(readFile(dir_ / "csv" / "ratings.csv"),
            "meal,n,mean,sd,method,n_ranked,zeros,w_plus,w_minus,z,p_two_sided,p_greater,r\n"
            "1,1,5.0000,,exact,1,0,1.0,0.0,0.0000,1,0.5,0.0000\n"
            "2,1,5.0000,,exact,1,0,1.0,0.0,0.0000,1,0.5,0.0000\n"
            "3,1,5.0000,,exact,1,0,1.0,0.0,0.0000,1,0.5,0.0000\n"
            "4,1,5.0000,,exact,1,0,1.0,0.0,0.0000,1,0.5,0.0000\n"
            "5,1,4.0000,,exact,1,0,1.0,0.0,0.0000,1,0.5,0.0000\n");
  // Meal 1 shown whole; every meal the same: CBTL right and met everywhere; No Personalization (noDip mouthOpen
  // chatty) never right, met dip and signal; one picture, not blocked. Meal 5's signal mouthOpen matches it.
  const std::string accuracy = readFile(dir_ / "csv" / "accuracy.csv");
  const std::string meal1 =
      "meal,measure,approach,question,hits,total,share\n"
      "1,predicted,cbtl,dip,1,1,1.0000\n"
      "1,predicted,cbtl,signal,1,1,1.0000\n"
      "1,predicted,cbtl,verbosity,1,1,1.0000\n"
      "1,predicted,no-personalization,dip,0,1,0.0000\n"
      "1,predicted,no-personalization,signal,0,1,0.0000\n"
      "1,predicted,no-personalization,verbosity,0,1,0.0000\n"
      "1,met,cbtl,dip,1,1,1.0000\n"
      "1,met,cbtl,signal,1,1,1.0000\n"
      "1,met,cbtl,verbosity,1,1,1.0000\n"
      "1,met,cbtl,view,1,1,1.0000\n"
      "1,met,no-personalization,dip,1,1,1.0000\n"
      "1,met,no-personalization,signal,1,1,1.0000\n"
      "1,met,no-personalization,verbosity,0,1,0.0000\n"
      "1,met,no-personalization,view,0,0,\n"
      "1,not_blocked,,,1,1,1.0000\n";
  EXPECT_EQ(accuracy.substr(0, meal1.size()), meal1);
  EXPECT_EQ(std::count(accuracy.begin(), accuracy.end(), '\n'), 1 + 5 * 15);
  EXPECT_NE(accuracy.find("5,predicted,no-personalization,signal,1,1,1.0000\n"), std::string::npos);
  EXPECT_EQ(readFile(dir_ / "csv" / "paths.csv"),
            "question,path,count\n"
            "dip,hummus > hummus > hummus > hummus > hummus,1\n"
            "signal,button > button > button > button > mouthOpen,1\n"
            "verbosity,silent > silent > silent > silent > silent,1\n");
  EXPECT_EQ(readFile(dir_ / "csv" / "flows.csv"),
            "question,meal_from,answer_from,meal_to,answer_to,count\n"
            "dip,1,hummus,2,hummus,1\n"
            "dip,2,hummus,3,hummus,1\n"
            "dip,3,hummus,4,hummus,1\n"
            "dip,4,hummus,5,hummus,1\n"
            "signal,1,button,2,button,1\n"
            "signal,2,button,3,button,1\n"
            "signal,3,button,4,button,1\n"
            "signal,4,button,5,mouthOpen,1\n"
            "verbosity,1,silent,2,silent,1\n"
            "verbosity,2,silent,3,silent,1\n"
            "verbosity,3,silent,4,silent,1\n"
            "verbosity,4,silent,5,silent,1\n");
  // rt_ms = 1000 (t + 1): consent 1000, demographics 2000, ratings 3000..11000, answers 4000..12000, complete 13000;
  // rating p90 at 3.6: 9000 + 0.6 * 2000; total: elapsed_ms = 60000 * 13.
  EXPECT_EQ(readFile(dir_ / "csv" / "times.csv"),
            "measure,n,median_ms,p90_ms\n"
            "consent,1,1000.0,1000.0\n"
            "demographics,1,2000.0,2000.0\n"
            "rating,5,7000.0,10200.0\n"
            "answers,5,8000.0,11200.0\n"
            "complete,1,13000.0,13000.0\n"
            "total,1,780000.0,780000.0\n");
}

}  // namespace
}  // namespace cbtl::app::study
