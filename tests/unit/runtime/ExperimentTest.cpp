// The experiment loop on Cooking: end to end, deterministic, learning, and the paper's switches.
#include "tests/unit/runtime/TestPrograms.h"

#include "app/DomainSolverOptions.h"
#include "app/SimulatorSource.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <vector>

#include <filesystem>

using namespace cbtl;

namespace {

approach::SimulatorFactory cooking() {
  return [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator("cooking", {}, o, seed);
  };
}

approach::ExperimentConfig shortRun(approach::ApproachKind kind, std::uint64_t seed, const std::string& out = "") {
  approach::ExperimentConfig c;
  c.approach.kind = kind;
  c.seed = seed;
  c.steps = 600;
  c.evalEvery = 200;
  c.evalTasks = 3;
  c.outDir = out;
  return c;
}

// Per process: two test runs on one machine (make test beside make asan) must not share a folder. The
// folders go when the test program ends.
struct TempDirs : ::testing::Environment {
  static std::vector<std::filesystem::path>& made() {
    static std::vector<std::filesystem::path> paths;
    return paths;
  }
  void TearDown() override {
    for (const auto& p : made()) std::filesystem::remove_all(p);
  }
};
[[maybe_unused]] ::testing::Environment* const kTempDirs = ::testing::AddGlobalTestEnvironment(new TempDirs);

std::string tempDir(const std::string& name) {
  const auto p = std::filesystem::temp_directory_path() / ("cbtl_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(p);
  TempDirs::made().push_back(p);
  return p.string();
}

}  // namespace

TEST(Experiment, ShortCookingRunLearnsAndWritesItsFiles) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const std::string out = tempDir("short");
  const auto r = approach::runExperiment(*lp, cooking(), shortRun(approach::ApproachKind::Cbtl, 0, out));
  ASSERT_EQ(r.evals.size(), 4u);  // steps 0, 200, 400, 600
  EXPECT_EQ(r.evals.front().step, 0);
  EXPECT_EQ(r.evals.back().step, 600);
  EXPECT_GT(r.mealsServed, 10);
  EXPECT_EQ(r.trainSolveFailures, 0);
  for (const char* f : {"train.csv", "eval.csv", "config.json", "profile.json", "models/0.json", "models/600.json"}) {
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / f)) << f;
  }
  const std::string train = test::readFile(out + "/train.csv");
  EXPECT_EQ(train.rfind("step,execution_time,user_satisfaction", 0), 0u);
  EXPECT_EQ(std::count(train.begin(), train.end(), '\n'), 601);
  model::UserModel learned(lp->graph());
  learned.load(out + "/profile.json");
  EXPECT_GT(learned.dataCount(), 20u) << "every served meal labels two ingredients on two axes";
}

TEST(Experiment, SameSeedGivesIdenticalCsvs) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  const std::string a = tempDir("det_a"), b = tempDir("det_b"), c = tempDir("det_c");
  approach::runExperiment(*lp, cooking(), shortRun(approach::ApproachKind::EpsilonGreedy, 4, a));
  approach::runExperiment(*lp, cooking(), shortRun(approach::ApproachKind::EpsilonGreedy, 4, b));
  approach::runExperiment(*lp, cooking(), shortRun(approach::ApproachKind::EpsilonGreedy, 5, c));
  EXPECT_EQ(test::readFile(a + "/train.csv"), test::readFile(b + "/train.csv"));
  EXPECT_EQ(test::readFile(a + "/eval.csv"), test::readFile(b + "/eval.csv"));
  EXPECT_EQ(test::readFile(a + "/profile.json"), test::readFile(b + "/profile.json"));
  EXPECT_NE(test::readFile(a + "/train.csv"), test::readFile(c + "/train.csv"));
}

// A checkpoint's evaluation measures the models at that step, whatever the evaluation schedule: the evaluation
// solver starts afresh at every checkpoint. Before, it carried its random stream and its memory of satisfying
// values from one evaluation to the next; in Feeding (seed 0, 200 steps) the configurations evaluated at step 200
// then differed between --eval-every 100 and 300, which showed in the clearance to the user (6.13 mm against
// 7.06 mm at the closest), while the satisfaction happened to agree. Cooking's satisfaction did not show it.
TEST(Experiment, ACheckpointsEvaluationDoesNotDependOnTheEvaluationsBeforeIt) {
  auto lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  approach::ExperimentConfig often;
  often.approach.kind = approach::ApproachKind::Cbtl;
  often.seed = 0;
  often.steps = 200;
  often.evalEvery = 100;
  often.evalTasks = 4;
  often.solverOptions = app::domainSolverOptions(lp->graph().domain);
  auto once = often;
  once.evalEvery = 300;
  const auto factory = app::simulatorFactory(*lp, std::nullopt);
  const auto a = approach::runExperiment(*lp, factory, often);
  const auto b = approach::runExperiment(*lp, factory, once);
  ASSERT_EQ(a.evals.size(), 3u);
  ASSERT_EQ(b.evals.size(), 2u);
  const approach::EvalPoint& x = a.evals.back();
  const approach::EvalPoint& y = b.evals.back();
  EXPECT_EQ(x.step, y.step);
  EXPECT_EQ(x.satisfaction, y.satisfaction);
  ASSERT_FALSE(x.measures.empty()) << "Feeding reports the clearance to the user of every bite and drink";
  ASSERT_EQ(x.measures.size(), y.measures.size());
  for (const auto& [name, tally] : x.measures) {
    ASSERT_TRUE(y.measures.count(name)) << name;
    EXPECT_EQ(tally.count, y.measures.at(name).count) << name;
    EXPECT_EQ(tally.min, y.measures.at(name).min) << name;
    EXPECT_EQ(tally.sum, y.measures.at(name).sum) << name;
  }
}

TEST(Experiment, NoPersonalizationNeverLearns) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  const std::string out = tempDir("nolearn");
  approach::runExperiment(*lp, cooking(), shortRun(approach::ApproachKind::NoPersonalization, 1, out));
  model::UserModel learned(lp->graph());
  learned.load(out + "/profile.json");
  EXPECT_EQ(learned.dataCount(), 0u);
}

TEST(Experiment, CbtlLearnsTheHiddenRangesWithinFifteenHundredSteps) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  const std::string out = tempDir("learns");
  auto c = shortRun(approach::ApproachKind::Cbtl, 2, out);
  c.steps = 1500;
  c.evalEvery = 1500;
  c.evalTasks = 10;
  const auto r = approach::runExperiment(*lp, cooking(), c);
  EXPECT_EQ(r.evals.front().mean, -1.0) << "nothing is known at step 0";
  EXPECT_GT(r.evals.back().mean, 0.0);
  // The hidden user likes 28 .. 32 ticks and 0.95 .. 1.0 of each seasoning. Entropy-driven exploration
  // bisects the ramps: each boundary is pinned between a negative and a positive example.
  model::UserModel learned(lp->graph());
  learned.load(out + "/profile.json");
  for (const char* ing : {"salt", "pepper"}) {
    const auto& f = learned.generator(0).factors(std::string("seasoning|") + ing);
    const auto& temp = std::get<model::IntervalModel>(f[0].model());
    const auto& qty = std::get<model::IntervalModel>(f[1].model());
    EXPECT_TRUE(temp.x1() < 28 && 28 <= temp.x2() && temp.x2() - temp.x1() <= 1) << ing;
    EXPECT_TRUE(temp.x3() <= 32 && 32 < temp.x4() && temp.x4() - temp.x3() <= 1) << ing;
    EXPECT_TRUE(qty.x1() < 0.95 && 0.95 <= qty.x2() && qty.x2() - qty.x1() < 0.01) << ing;
    EXPECT_TRUE(qty.x3() <= 1.0 && 1.0 < qty.x4() && qty.x4() - qty.x3() < 0.01) << ing;
  }
}

TEST(Experiment, UnsatisfiableStockWithAndWithoutReplanning) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  auto c = shortRun(approach::ApproachKind::Cbtl, 3);
  c.steps = 1500;
  c.evalEvery = 1500;
  c.evalTasks = 10;
  c.simulator.unsatisfiableStockProbability = 0.5;
  const auto noReplan = approach::runExperiment(*lp, cooking(), c);
  c.approach.replan = true;
  const auto replan = approach::runExperiment(*lp, cooking(), c);
  EXPECT_LT(noReplan.evals.back().taskSuccessRate, 1.0);
  EXPECT_EQ(noReplan.evals.back().replans, 0);
  EXPECT_EQ(replan.evals.back().taskSuccessRate, 1.0);
  EXPECT_GT(replan.evals.back().replans, 0);
}

TEST(Experiment, NonstationaryUserResetForgetsOnAnnouncedShifts) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  const std::string out = tempDir("reset");
  auto c = shortRun(approach::ApproachKind::Cbtl, 6, out);
  c.steps = 700;
  c.nonstationary = true;
  c.adaptation = approach::Adaptation::UserReset;
  c.simulator.shiftEvery = 650;
  approach::runExperiment(*lp, cooking(), c);
  model::UserModel at600(lp->graph()), at700(lp->graph());
  at600.load(out + "/models/600.json");
  at700.load(out + "/profile.json");
  EXPECT_LT(at700.dataCount(), at600.dataCount()) << "the models were reset at step 650";
}

TEST(Experiment, BadConfigurationIsRejected) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  auto c = shortRun(approach::ApproachKind::Cbtl, 0);
  c.task = "nope";
  EXPECT_THROW(approach::runExperiment(*lp, cooking(), c), std::runtime_error);
  c.task = "";
  c.evalEvery = 0;
  EXPECT_THROW(approach::runExperiment(*lp, cooking(), c), std::runtime_error);
  c.evalEvery = 10;
  c.initialProfile = "/nonexistent.json";
  EXPECT_THROW(approach::runExperiment(*lp, cooking(), c), std::exception);
}
