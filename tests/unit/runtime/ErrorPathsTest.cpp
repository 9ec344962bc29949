// Error paths: which exception each failure raises, and the exit code `cbtl` maps it to (ErrorHandling.h).
#include "tests/unit/runtime/TestPrograms.h"

#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"
#include "runtime/core/InternalError.h"
#include "runtime/core/Values.h"
#include "runtime/model/UserModel.h"
#include "tools/cbtl/ErrorHandling.h"

#include <gtest/gtest.h>
#include <CLI/CLI.hpp>

#include <new>

using namespace cbtl;

namespace {

// Cooking, except that every action is answered with UnknownAction: a simulator that breaks the contract.
class RejectingSimulator : public sim::DomainSimulator {
 public:
  explicit RejectingSimulator(std::unique_ptr<sim::DomainSimulator> inner) : inner_(std::move(inner)) {}
  void reset(std::uint64_t seed) override { inner_->reset(seed); }
  sim::Observation observe() const override { return inner_->observe(); }
  sim::StepResult act(const sim::ActionCall&) override {
    sim::StepResult r;
    r.status = sim::ActionStatus::UnknownAction;
    r.message = "no such action";
    return r;
  }
  sim::StepResult idle() override { return inner_->idle(); }
  std::string requestedTask() const override { return inner_->requestedTask(); }
  std::unique_ptr<sim::DomainSimulator> makeEvaluationTwin() const override {
    return std::make_unique<RejectingSimulator>(inner_->makeEvaluationTwin());
  }

 private:
  std::unique_ptr<sim::DomainSimulator> inner_;
};

// Cooking, except that every step's feedback also carries an event the program does not declare.
class ChattySimulator : public sim::DomainSimulator {
 public:
  explicit ChattySimulator(std::unique_ptr<sim::DomainSimulator> inner) : inner_(std::move(inner)) {}
  void reset(std::uint64_t seed) override { inner_->reset(seed); }
  sim::Observation observe() const override { return inner_->observe(); }
  sim::StepResult act(const sim::ActionCall& call) override { return chat(inner_->act(call)); }
  sim::StepResult idle() override { return chat(inner_->idle()); }
  std::string requestedTask() const override { return inner_->requestedTask(); }
  std::unique_ptr<sim::DomainSimulator> makeEvaluationTwin() const override {
    return std::make_unique<ChattySimulator>(inner_->makeEvaluationTwin());
  }

 private:
  static sim::StepResult chat(sim::StepResult r) {
    if (r.consumedStep) r.feedback.push_back({"spilled", {}});
    return r;
  }
  std::unique_ptr<sim::DomainSimulator> inner_;
};

approach::ExperimentConfig tinyRun() {
  approach::ExperimentConfig c;
  c.steps = 20;
  c.evalEvery = 10;
  c.evalTasks = 1;
  c.maxEvalEpisodeSteps = 5;
  return c;
}

int exitCodeOf(const std::function<int()>& body) {
  int code = -1;
  cli::runCommand("test", code, body);
  return code;
}

}  // namespace

TEST(ErrorPaths, UnknownActionIsAnInternalError) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const approach::SimulatorFactory factory = [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return std::make_unique<RejectingSimulator>(domains::createSimulator("cooking", {}, o, seed));
  };
  EXPECT_THROW(approach::runExperiment(*lp, factory, tinyRun()), rt::InternalError);
}

// Before, an undeclared event was dropped: the run exited 0 and nothing was learned from it.
TEST(ErrorPaths, AnUndeclaredFeedbackEventIsBadInputNamingIt) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const approach::SimulatorFactory factory = [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return std::make_unique<ChattySimulator>(domains::createSimulator("cooking", {}, o, seed));
  };
  try {
    approach::runExperiment(*lp, factory, tinyRun());
    ADD_FAILURE() << "an undeclared event was accepted";
  } catch (const std::logic_error& e) {
    ADD_FAILURE() << "bad input reported as a bug: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("event 'spilled' is not declared by the program"), std::string::npos)
        << e.what();
  }
}

TEST(ErrorPaths, PeriodicResetEveryMustBePositive) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const approach::SimulatorFactory factory = [](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator("cooking", {}, o, seed);
  };
  for (std::int64_t every : {std::int64_t{0}, std::int64_t{-5}}) {
    approach::ExperimentConfig c = tinyRun();
    c.nonstationary = true;
    c.adaptation = approach::Adaptation::PeriodicReset;
    c.periodicResetEvery = every;
    try {
      approach::runExperiment(*lp, factory, c);
      ADD_FAILURE() << "periodicResetEvery " << every << " was accepted";
    } catch (const std::logic_error& e) {
      ADD_FAILURE() << "bad input reported as a bug: " << e.what();
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("periodic-reset-every"), std::string::npos) << e.what();
    }
  }
}

TEST(ErrorPaths, ExceptionTypesMapToExitCodes) {
  EXPECT_EQ(exitCodeOf([] { return 0; }), 0);
  EXPECT_EQ(exitCodeOf([] { return 3; }), 3);
  EXPECT_EQ(exitCodeOf([]() -> int { throw model::ProfileError("p.json: generators: bad"); }), 1);
  EXPECT_EQ(exitCodeOf([]() -> int { throw rt::RuntimeError("f.cbtl:1:1", "no built-in"); }), 1);
  EXPECT_EQ(exitCodeOf([]() -> int { throw std::runtime_error("cannot write"); }), 1);
  EXPECT_EQ(exitCodeOf([]() -> int { throw cli::UsageError("--columns: x"); }), 2);
  EXPECT_EQ(exitCodeOf([]() -> int { throw rt::InternalError("broken"); }), 70);
  EXPECT_EQ(exitCodeOf([]() -> int { throw std::out_of_range("vector::at"); }), 70);
  EXPECT_EQ(exitCodeOf([]() -> int { throw std::bad_alloc(); }), 70);
  EXPECT_EQ(exitCodeOf([]() -> int { throw 42; }), 70);
}

TEST(ErrorPaths, MessagesNameTheCommandAndCallBugsBugs) {
  testing::internal::CaptureStderr();
  exitCodeOf([]() -> int { throw rt::InternalError("the simulator rejected action 'x'"); });
  const std::string bug = testing::internal::GetCapturedStderr();
  EXPECT_NE(bug.find("cbtl test: error: internal error: the simulator rejected action 'x'"), std::string::npos) << bug;
  EXPECT_NE(bug.find("this is a bug"), std::string::npos) << bug;
  testing::internal::CaptureStderr();
  exitCodeOf([]() -> int { throw std::runtime_error("cannot read 'f'"); });
  const std::string input = testing::internal::GetCapturedStderr();
  EXPECT_EQ(input, "cbtl test: error: cannot read 'f'\n");
}

TEST(ErrorPaths, ParseErrorsGoBackToCli11) {
  int code = -1;
  EXPECT_THROW(cli::runCommand("test", code, []() -> int { throw CLI::ValidationError("--x", "bad"); }),
               CLI::ParseError);
}
