// Results are never lost or mixed: a run folder that holds a run is refused, replaced (--force) or resumed
// (--resume); a resumed Cooking run writes the same bytes as an uninterrupted one without solving the steps
// before its checkpoint again; a second process cannot share the folder; failed writes name their file.
#include "tests/unit/runtime/TestPrograms.h"

#include "domains/DomainRegistry.h"
#include "runtime/approach/Checkpoint.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/RunDirectory.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

using namespace cbtl;
namespace fs = std::filesystem;

namespace {

approach::SimulatorFactory cooking() {
  return [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator("cooking", {}, o, seed);
  };
}

// Per process: two test runs on one machine (make test beside make asan) must not share a folder. The
// folders go when the test program ends.
struct TempDirs : ::testing::Environment {
  static std::vector<fs::path>& made() {
    static std::vector<fs::path> paths;
    return paths;
  }
  void TearDown() override {
    for (const auto& p : made()) fs::remove_all(p);
  }
};
[[maybe_unused]] ::testing::Environment* const kTempDirs = ::testing::AddGlobalTestEnvironment(new TempDirs);

std::string tempDir(const std::string& name) {
  const auto p = fs::temp_directory_path() / ("cbtl_resume_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(p);
  TempDirs::made().push_back(p);
  return p.string();
}

struct Interrupted {};

struct Variant {
  const char* name;
  approach::ApproachKind kind;
  bool nonstationary;
};

approach::ExperimentConfig config(const Variant& v, const std::string& out) {
  approach::ExperimentConfig c;
  c.approach.kind = v.kind;
  c.seed = 7;
  c.steps = 1000;
  c.evalEvery = 100;
  c.evalTasks = 2;
  c.outDir = out;
  if (v.nonstationary) {
    c.nonstationary = true;
    c.adaptation = approach::Adaptation::UserReset;
    c.simulator.shiftEvery = 150;
  }
  return c;
}

// A run in a fresh LoadedProgram, as a new process would load it (its interned texts start afresh).
approach::ExperimentResult runFresh(approach::ExperimentConfig c) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  if (!lp->ok()) throw std::runtime_error(lp->errors());
  return approach::runExperiment(*lp, cooking(), c);
}

std::vector<std::string> filesOf(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& rel : approach::runFilesIn(dir)) {
    if (rel == "config.json" || rel == "complete.json") continue;  // config.json is the same by construction
    out.push_back(rel);
  }
  return out;
}

void expectSameResults(const std::string& a, const std::string& b) {
  const auto files = filesOf(a);
  ASSERT_EQ(files, filesOf(b));
  EXPECT_NE(std::find(files.begin(), files.end(), "profile.json"), files.end());
  for (const auto& f : files) {
    if (f == "timing.json") continue;  // wall-clock seconds: present in both, never a result
    EXPECT_EQ(test::readFile(a + "/" + f), test::readFile(b + "/" + f)) << f << " differs";
  }
}

struct Point {
  const char* point;
  std::int64_t step;
};

void PrintTo(const Variant& v, std::ostream* os) { *os << v.name; }
void PrintTo(const Point& p, std::ostream* os) { *os << p.point << ":" << p.step; }

class ResumeTest : public ::testing::TestWithParam<std::tuple<Variant, Point>> {};

}  // namespace

// Interrupt (an exception drops the unflushed rows as a kill would) at one point, resume, compare every file.
TEST_P(ResumeTest, ResumedRunWritesTheBytesOfAnUninterruptedOne) {
  const auto& [variant, stop] = GetParam();
  const std::string name = fmt::format("{}_{}_{}", variant.name, stop.point, stop.step);
  const std::string whole = tempDir(name + "_whole"), cut = tempDir(name + "_cut");
  const auto expected = runFresh(config(variant, whole));

  approach::ExperimentConfig c = config(variant, cut);
  c.testHook = [&](const char* point, std::int64_t step) {
    if (step == stop.step && std::string(point) == stop.point) throw Interrupted{};
  };
  EXPECT_THROW(runFresh(c), Interrupted);
  EXPECT_FALSE(fs::exists(cut + "/complete.json"));

  // The checkpoint the resume starts from: the last evaluation point whose checkpoint.json was written.
  std::int64_t from = -1;
  if (fs::exists(cut + "/checkpoint.json"))
    from = nlohmann::json::parse(test::readFile(cut + "/checkpoint.json")).at("step");
  std::vector<std::pair<std::string, std::int64_t>> calls;
  c.runMode = approach::RunMode::Resume;
  c.testHook = [&](const char* point, std::int64_t step) { calls.emplace_back(point, step); };
  const auto resumed = runFresh(c);

  expectSameResults(whole, cut);
  EXPECT_TRUE(fs::exists(cut + "/complete.json"));
  EXPECT_FALSE(fs::exists(cut + "/checkpoint.json")) << "a complete run drops its resume state";
  EXPECT_FALSE(resumed.finishedEarlier) << "it ran here";

  // Resumed again, the complete run is read back with the time its parts took (timing.json), not re-run.
  const double recorded = nlohmann::json::parse(test::readFile(cut + "/timing.json")).at("seconds");
  EXPECT_GT(recorded, 0.0);
  const auto readBack = runFresh(c);
  EXPECT_TRUE(readBack.finishedEarlier);
  ASSERT_TRUE(readBack.recordedSeconds.has_value());
  EXPECT_DOUBLE_EQ(*readBack.recordedSeconds, recorded);
  ASSERT_FALSE(calls.empty());
  // Nothing before the checkpoint ran again: the first training step is the checkpoint's, and its evaluation
  // (the "model" point) is not repeated.
  for (const auto& [point, step] : calls) {
    if (from >= 0) {
      EXPECT_GE(step, from) << point;
    }
    if (point == "model") {
      EXPECT_GT(step, from);
    }
  }
  EXPECT_EQ(resumed.mealsServed, expected.mealsServed);
  EXPECT_EQ(resumed.trainSolves, expected.trainSolves);
  EXPECT_EQ(resumed.solverIterations, expected.solverIterations);
  EXPECT_EQ(resumed.trainSatisfaction, expected.trainSatisfaction);
  ASSERT_EQ(resumed.evals.size(), expected.evals.size());
  for (std::size_t i = 0; i < resumed.evals.size(); ++i)
    EXPECT_EQ(resumed.evals[i].satisfaction, expected.evals[i].satisfaction);
}

INSTANTIATE_TEST_SUITE_P(
    Cooking, ResumeTest,
    ::testing::Combine(::testing::Values(Variant{"cbtl", approach::ApproachKind::Cbtl, false},
                                         Variant{"epsilon_shifting", approach::ApproachKind::EpsilonGreedy, true}),
                       ::testing::Values(Point{"step", 537}, Point{"checkpoint", 600}, Point{"model", 300},
                                         Point{"model", 0}, Point{"finish", 1000}, Point{"step", 999})),
    [](const auto& param) {
      const Variant& v = std::get<0>(param.param);
      const Point& p = std::get<1>(param.param);
      return fmt::format("{}_{}_{}", v.name, p.point, p.step);
    });

TEST(RunDirectory, AFolderWithARunIsRefusedUnlessForcedOrResumed) {
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  const std::string dir = tempDir("refuse");
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 200;
  runFresh(c);
  try {
    runFresh(c);
    FAIL() << "a second run into the same folder was not refused";
  } catch (const approach::RunDirectoryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir), std::string::npos) << what;
    EXPECT_NE(what.find("--force"), std::string::npos) << what;
    EXPECT_NE(what.find("--resume"), std::string::npos) << what;
  }
  // --force replaces the run's files and nothing else.
  { std::ofstream(dir + "/notes.txt") << "mine"; }
  fs::create_directories(dir + "/models/extra");
  { std::ofstream(dir + "/models/readme.md") << "mine"; }
  { std::ofstream(dir + "/models/999.json") << "stale"; }
  c.runMode = approach::RunMode::Force;
  runFresh(c);
  EXPECT_EQ(test::readFile(dir + "/notes.txt"), "mine");
  EXPECT_TRUE(fs::exists(dir + "/models/readme.md"));
  EXPECT_TRUE(fs::is_directory(dir + "/models/extra"));
  EXPECT_FALSE(fs::exists(dir + "/models/999.json")) << "a stale model of the old run must not mix with the new one";
  EXPECT_TRUE(fs::exists(dir + "/complete.json"));
}

TEST(RunDirectory, ResumeWithOtherOptionsNamesTheDifferingKeys) {
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  const std::string dir = tempDir("differ");
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 300;
  c.testHook = [](const char* point, std::int64_t step) {
    if (step == 150 && std::string(point) == "step") throw Interrupted{};
  };
  EXPECT_THROW(runFresh(c), Interrupted);
  c.testHook = nullptr;
  c.runMode = approach::RunMode::Resume;
  c.steps = 400;
  c.seed = 8;
  try {
    runFresh(c);
    FAIL() << "a resume with other options was accepted";
  } catch (const approach::RunDirectoryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("steps (this command: 400, the run: 300)"), std::string::npos) << what;
    EXPECT_NE(what.find("seed"), std::string::npos) << what;
    EXPECT_EQ(what.find("eval_every"), std::string::npos) << what;
  }
}

TEST(RunDirectory, ResumingACompleteRunRunsNothing) {
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  const std::string dir = tempDir("complete");
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 200;
  const auto first = runFresh(c);
  const std::string train = test::readFile(dir + "/train.csv");
  c.runMode = approach::RunMode::Resume;
  int calls = 0;
  c.testHook = [&](const char*, std::int64_t) { ++calls; };
  const auto again = runFresh(c);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(again.mealsServed, first.mealsServed);
  ASSERT_EQ(again.evals.size(), first.evals.size());
  EXPECT_EQ(again.evals.back().satisfaction, first.evals.back().satisfaction);
  EXPECT_EQ(test::readFile(dir + "/train.csv"), train);
}

// A finished run of an earlier format (whose evaluation was measured differently) is not read back as if it
// were this version's result.
TEST(RunDirectory, ACompleteRunOfAnEarlierFormatIsNotReused) {
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  const std::string dir = tempDir("old_format");
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 200;
  runFresh(c);
  std::string marker = test::readFile(dir + "/complete.json");
  const auto at = marker.find("\"version\": ");
  ASSERT_NE(at, std::string::npos) << marker;
  marker.replace(at, std::string("\"version\": 3").size(), "\"version\": 2");
  { std::ofstream(dir + "/complete.json") << marker; }
  c.runMode = approach::RunMode::Resume;
  try {
    runFresh(c);
    FAIL() << "an earlier format's result was reused";
  } catch (const approach::RunDirectoryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("earlier cbtl (format version 2, this one writes 3)"), std::string::npos) << what;
  }
}

TEST(RunDirectory, ResumeRemovesTheTemporariesOfAKilledWrite) {
  // kill -9 during an atomic write leaves "<file>.tmp.<pid>.<n>"; a resumed run must not keep them (found by
  // results_cli.sh's kill at an arbitrary moment).
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  const std::string dir = tempDir("temporaries");
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 200;
  runFresh(c);
  std::ofstream(dir + "/models/300.json.tmp.4242.0") << "{";
  std::ofstream(dir + "/checkpoint.json.tmp.4242.1") << "{";
  std::ofstream(dir + "/notes.tmp.txt") << "mine";  // not a run file: left alone
  c.runMode = approach::RunMode::Resume;
  runFresh(c);
  EXPECT_FALSE(fs::exists(dir + "/models/300.json.tmp.4242.0"));
  EXPECT_FALSE(fs::exists(dir + "/checkpoint.json.tmp.4242.1"));
  EXPECT_TRUE(fs::exists(dir + "/notes.tmp.txt"));
}

TEST(RunDirectory, ASecondProcessCannotShareTheFolder) {
  const std::string dir = tempDir("lock");
  fs::create_directories(dir);
  approach::DirectoryLock held(dir);  // flock(2) conflicts between open file descriptions, even in one process
  const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
  approach::ExperimentConfig c = config(v, dir);
  c.steps = 100;
  try {
    runFresh(c);
    FAIL() << "the run did not notice the lock";
  } catch (const approach::RunDirectoryError& e) {
    EXPECT_NE(std::string(e.what()).find("in use by another cbtl process"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(approach::runFilesIn(dir).empty()) << "the refused run wrote files";
}

TEST(RunDirectory, AFullDeviceIsReportedWithTheFileNamed) {
  approach::AppendFile f;
  f.open("/dev/full");
  f.append("a row\n");
  try {
    f.flush();
    FAIL() << "a write to /dev/full succeeded";
  } catch (const approach::RunDirectoryError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
  }
  // Every file of a run: the injected failure (CBTL_TEST_WRITE_FAILS) makes each one fail in turn.
  for (const char* file : {"train.csv", "eval.csv", "world-calls.jsonl", "checkpoint.json", "config.json", "0.json",
                           "profile.json", "complete.json"}) {
    const std::string dir = tempDir(std::string("full_") + file);
    ::setenv("CBTL_TEST_WRITE_FAILS", file, 1);
    const Variant v{"cbtl", approach::ApproachKind::Cbtl, false};
    approach::ExperimentConfig c = config(v, dir);
    c.steps = 100;
    try {
      runFresh(c);
      ADD_FAILURE() << "a failed write to " << file << " went unnoticed";
    } catch (const approach::RunDirectoryError& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
    ::unsetenv("CBTL_TEST_WRITE_FAILS");
    EXPECT_FALSE(fs::exists(dir + "/complete.json")) << file;
  }
}

TEST(RunDirectory, RunFileNamesAreOnlyTheRunsOwn) {
  for (const char* f :
       {"train.csv", "eval.csv", "config.json", "profile.json", "checkpoint.json", "world-calls.jsonl",
        "motions.jsonl.gz", "complete.json", "models/0.json", "models/12000.json", "profile.json.tmp.123.4"}) {
    EXPECT_TRUE(approach::isRunFileName(f)) << f;
  }
  for (const char* f : {"notes.txt", "models/best.json", "models/1.json.bak", "train.csv.bak", "summary.csv", ".lock",
                        "profile.json.tmp", "models/sub/1.json"}) {
    EXPECT_FALSE(approach::isRunFileName(f)) << f;
  }
}

TEST(RunDirectory, RngAndSolverStatesRoundTrip) {
  rt::Rng a(42);
  for (int i = 0; i < 10; ++i) a.next();
  rt::Rng b(1);
  ASSERT_TRUE(b.restoreState(a.saveState()));
  for (int i = 0; i < 5; ++i) EXPECT_EQ(a.next(), b.next());
  EXPECT_FALSE(b.restoreState("not a state"));
  solver::Solver s({}, 3);
  EXPECT_THROW(s.restoreState(nlohmann::json{{"rng", "x"}}), std::runtime_error);
  solver::SolverOptions other;
  other.memorySize = 7;
  EXPECT_THROW(solver::Solver(other, 3).restoreState(s.saveState()), std::runtime_error);
}
