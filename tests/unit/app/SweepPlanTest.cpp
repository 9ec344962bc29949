// app/sweep: a sweep's JSON config read and checked, expanded into trials in a fixed order with their folders and
// `cbtl run` options, and split into SLURM array tasks within the cluster's limits.
#include "app/sweep/SweepConfig.h"
#include "app/sweep/SweepPlan.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace cbtl::sweep {
namespace {

namespace fs = std::filesystem;

class SweepPlanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cbtl-sweep-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "domains");
    std::ofstream(dir_ / "domains" / "d.cbtl") << "domain d;\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string config(const std::string& text) {
    const fs::path p = dir_ / "sweep.json";
    std::ofstream(p) << text;
    return p.string();
  }
  // The message readSweepConfig throws for `text`.
  std::string error(const std::string& text) {
    try {
      readSweepConfig(config(text));
    } catch (const SweepError& e) {
      return e.what();
    }
    return "(accepted)";
  }
  fs::path dir_;
};

TEST_F(SweepPlanTest, ExpandsTheGridInOrderWithFoldersAndOptions) {
  const SweepConfig c = readSweepConfig(config(R"({
    "defaults": {"steps": 100, "eval-every": 50, "replan": true},
    "experiments": [
      {"name": "a", "program": "domains/d.cbtl", "approaches": ["cbtl", "free-explore"], "seeds": "3..4",
       "options": {"steps": 200, "replan": false}},
      {"name": "b", "program": "domains/d.cbtl", "approaches": ["cbtl"], "seeds": "7",
       "grid": {"nonstationary": ["no-adapt", "user-reset"], "shift-every": [10, 20]}}
    ]})"));
  EXPECT_EQ(c.name, "sweep");
  EXPECT_EQ(c.experiments[0].program, (dir_ / "domains" / "d.cbtl").string()) << "relative to the config's folder";
  const SweepPlan plan = planSweep(c, "/out");
  ASSERT_EQ(plan.experiments.size(), 5u);
  ASSERT_EQ(plan.trials.size(), 8u);
  EXPECT_EQ(plan.experiments[0].arguments, (std::vector<std::string>{"--eval-every", "50", "--steps", "200"}))
      << "the experiment's options override the defaults; false leaves a flag out";
  EXPECT_EQ(plan.trials[1].dir, "/out/a/cbtl/seed4");
  EXPECT_EQ(plan.trials[2].approach, "free-explore");
  EXPECT_EQ(plan.experiments[1].name, "b/nonstationary=no-adapt,shift-every=10");
  EXPECT_EQ(plan.experiments[2].name, "b/nonstationary=no-adapt,shift-every=20") << "the last grid option fastest";
  EXPECT_EQ(plan.experiments[4].name, "b/nonstationary=user-reset,shift-every=20");
  EXPECT_EQ(plan.experiments[4].arguments,
            (std::vector<std::string>{"--eval-every", "50", "--replan", "--steps", "100", "--nonstationary",
                                      "user-reset", "--shift-every", "20"}));
  EXPECT_EQ(plan.trials[7].dir, "/out/b/nonstationary=user-reset,shift-every=20/cbtl/seed7");
  for (std::size_t i = 0; i < plan.trials.size(); ++i) EXPECT_EQ(plan.trials[i].index, i);
}

TEST_F(SweepPlanTest, SplitsTrialsIntoArrayTasksWithinTheClustersLimit) {
  SweepConfig c = readSweepConfig(config(R"({"experiments": [
      {"name": "a", "program": "domains/d.cbtl", "approaches": ["cbtl"], "seeds": "0..9"}],
      "slurm": {"trials-per-task": 3, "array-limit": 2, "partition": "cpu", "sbatch": ["--account=lab"]}})"));
  const SweepPlan plan = planSweep(c, "/out");
  EXPECT_EQ(trialsPerTask(c, plan.trials.size()), 3u);
  EXPECT_EQ(trialsOfTask(c, plan, 0), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(trialsOfTask(c, plan, 3), (std::vector<std::size_t>{9}));
  EXPECT_TRUE(trialsOfTask(c, plan, 4).empty());
  const std::string script = slurmScript(c, plan, "/opt/cbtl");
  EXPECT_NE(script.find("#SBATCH --array=0-3%2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --partition=cpu\n#SBATCH --output=/out/slurm/%A_%a.log\n#SBATCH --account=lab\n"),
            std::string::npos)
      << script;
  c.slurm.maxArraySize = 2;  // 10 trials in at most 2 tasks: 5 each
  EXPECT_EQ(trialsPerTask(c, plan.trials.size()), 5u);
  EXPECT_NE(slurmScript(c, plan, "/opt/cbtl").find("#SBATCH --array=0-1%2\n"), std::string::npos);
}

TEST_F(SweepPlanTest, RefusesWhatWouldGoWrongNamingTheJsonPointer) {
  const std::string ok = R"("program": "domains/d.cbtl")";
  EXPECT_NE(error("{"), "(accepted)");
  EXPECT_NE(error(R"({"experiments": []})").find("/experiments: needs an array"), std::string::npos);
  EXPECT_NE(
      error(R"({"experiments": [{"name": "a", )" + ok + R"(, "seed": "1"}]})").find("/experiments/0/seed: unknown key"),
      std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a/b", )" + ok + "}]}").find("/experiments/0/name"), std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a", )" + ok + R"(, "seeds": "9..1"}]})").find("/experiments/0/seeds"),
            std::string::npos);
  EXPECT_NE(error(R"({"defaults": {"out": "x"}, "experiments": [{"name": "a", )" + ok + "}]}")
                .find("/defaults/out: the sweep sets this option itself"),
            std::string::npos);
  EXPECT_NE(error(R"({"defaults": {"--steps": 3}, "experiments": [{"name": "a", )" + ok + "}]}").find("no dashes"),
            std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a", )" + ok + "}, {\"name\": \"a\", " + ok + "}]}")
                .find("/experiments/1/name: another experiment has this name"),
            std::string::npos);
  EXPECT_NE(
      error(R"({"experiments": [{"name": "a", "program": "nope.cbtl"}]})").find("/experiments/0/program: no such file"),
      std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a", )" + ok + R"(, "grid": {"steps": []}}]})")
                .find("/experiments/0/grid/steps"),
            std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a", )" + ok + R"(}], "plots": [{"out": "x.gif", "results": ["a"]}]})")
                .find("/plots/0/out: must end in .png, .svg or .pdf"),
            std::string::npos);
  EXPECT_NE(error(R"({"experiments": [{"name": "a", )" + ok + R"(}], "slurm": {"cpus-per-task": 0}})")
                .find("/slurm/cpus-per-task"),
            std::string::npos);
  // A plot naming no experiment of the sweep is refused when the sweep is planned.
  const SweepConfig c = readSweepConfig(
      config(R"({"experiments": [{"name": "a", )" + ok + R"(}], "plots": [{"out": "x.png", "results": ["b"]}]})"));
  EXPECT_THROW(planSweep(c, "/out"), SweepError);
}

TEST(SeedList, RangesListsAndRefusals) {
  std::vector<std::uint64_t> seeds;
  EXPECT_TRUE(parseSeedList("0..3", seeds));
  EXPECT_EQ(seeds, (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_TRUE(parseSeedList("5,1", seeds));
  EXPECT_EQ(seeds, (std::vector<std::uint64_t>{5, 1}));
  for (const char* bad : {"", "0-9", "-1", "3..1", "a", "1,,2", "0..20000", "1.5"})
    EXPECT_FALSE(parseSeedList(bad, seeds)) << bad;
}

}  // namespace
}  // namespace cbtl::sweep
