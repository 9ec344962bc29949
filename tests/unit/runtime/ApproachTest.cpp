// Each approach's CSPs: which include the personalized constraints, which maximize entropy, who learns and
// who falls back.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/approach/Approach.h"
#include "runtime/solver/Csp.h"

#include <gtest/gtest.h>

using namespace cbtl;
using approach::ApproachKind;
using solver::CostKind;
using solver::PersonalMode;

TEST(Approach, TrainingCspsAreThePapers) {
  rt::Rng rng(1);
  auto choice = [&](ApproachKind k) { return approach::trainingChoice({k, 0.5, false}, rng); };
  EXPECT_EQ(choice(ApproachKind::Cbtl).personal, PersonalMode::Exclude);
  EXPECT_EQ(choice(ApproachKind::Cbtl).cost, CostKind::Entropy);
  EXPECT_EQ(choice(ApproachKind::NoPersonalization).personal, PersonalMode::Exclude);
  EXPECT_EQ(choice(ApproachKind::NoPersonalization).cost, CostKind::Declared);
  EXPECT_EQ(choice(ApproachKind::FreeExplore).personal, PersonalMode::Exclude);
  EXPECT_EQ(choice(ApproachKind::ExploitOnly).personal, PersonalMode::Include);
  EXPECT_EQ(approach::evaluationChoice().personal, PersonalMode::Include);
  EXPECT_EQ(approach::evaluationChoice().cost, CostKind::Declared);
}

TEST(Approach, EpsilonGreedyDrawsItsCoinFromTheRunRng) {
  rt::Rng rng(5);
  int explore = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    if (approach::trainingChoice({ApproachKind::EpsilonGreedy, 0.5, false}, rng).personal == PersonalMode::Exclude)
      ++explore;
  }
  EXPECT_NEAR(explore / static_cast<double>(n), 0.5, 0.05);
  rt::Rng rng2(5);
  int explore2 = 0;
  for (int i = 0; i < n; ++i) {
    if (approach::trainingChoice({ApproachKind::EpsilonGreedy, 0.2, false}, rng2).personal == PersonalMode::Exclude)
      ++explore2;
  }
  EXPECT_NEAR(explore2 / static_cast<double>(n), 0.2, 0.05);
}

TEST(Approach, LearningAndFallback) {
  EXPECT_FALSE(approach::learns({ApproachKind::NoPersonalization, 0.5, false}));
  for (auto k :
       {ApproachKind::Cbtl, ApproachKind::FreeExplore, ApproachKind::ExploitOnly, ApproachKind::EpsilonGreedy}) {
    EXPECT_TRUE(approach::learns({k, 0.5, false}));
  }
  EXPECT_FALSE(approach::fallsBack({ApproachKind::Cbtl, 0.5, false}));
  EXPECT_TRUE(approach::fallsBack({ApproachKind::Cbtl, 0.5, true}));
  EXPECT_TRUE(approach::fallsBack({ApproachKind::ExploitOnly, 0.5, false}));
  EXPECT_TRUE(approach::fallsBack({ApproachKind::EpsilonGreedy, 0.5, false}));
  EXPECT_FALSE(approach::fallsBack({ApproachKind::FreeExplore, 0.5, false}));
}

TEST(Approach, NamesRoundTrip) {
  for (const auto& name : approach::approachNames()) {
    const auto k = approach::parseApproach(name);
    ASSERT_TRUE(k.has_value()) << name;
    EXPECT_EQ(approach::toString(*k), name);
  }
  EXPECT_FALSE(approach::parseApproach("ours").has_value());
}

TEST(Approach, CspContentsFollowTheChoice) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  model::UserModel user(lp->graph());
  const std::vector<double> obs(lp->program().observationWidth(), 15.0);
  auto count = [](const solver::Csp& c) {
    std::size_t personal = 0;
    for (const auto& r : c.constraints) personal += r.personal() ? 1 : 0;
    return personal;
  };
  const auto include =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, obs, PersonalMode::Include, CostKind::Declared);
  const auto exclude =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, obs, PersonalMode::Exclude, CostKind::Entropy);
  EXPECT_EQ(count(include), 4u);
  EXPECT_TRUE(include.constraints.front().personal()) << "personalized constraints are checked first";
  EXPECT_EQ(count(exclude), 0u);
  EXPECT_EQ(exclude.scoredInstances.size(), 4u);
  EXPECT_EQ(include.constraints.size() - 4, exclude.constraints.size());
  EXPECT_EQ(include.cost, CostKind::Likelihood) << "cooking declares no cost: exploiting picks the likeliest";
  EXPECT_EQ(include.scoredInstances.size(), 4u);
  const auto hardOnly =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, obs, PersonalMode::Exclude, CostKind::Declared);
  EXPECT_EQ(hardOnly.cost, CostKind::None) << "nothing personal to score: the first solution wins";
}
