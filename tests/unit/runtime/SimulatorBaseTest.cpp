// sim::SimulatorBase: what a training world shares with its evaluation twins, and what it does not.
#include "runtime/sim/SimulatorBase.h"

#include <gtest/gtest.h>

namespace cbtl::sim {
namespace {

struct Person {
  int patience = 3;
};

// A toy domain: the world is a counter drawn at reset; the user's patience is shared and only training changes it.
class CounterSimulator final : public SimulatorBase<CounterSimulator, Person> {
 public:
  CounterSimulator(const SimulatorOptions& options, std::uint64_t seed)
      : CounterSimulator(std::make_shared<Person>(), options, WorldRole::Training, seed) {}

  void reset(std::uint64_t seed) override {
    rng_.seed(seed);
    counter_ = static_cast<int>(rng_.index(1000));
  }
  Observation observe() const override { return {{"counter", Value::num(counter_)}}; }
  StepResult act(const ActionCall& call) override {
    if (call.name != "tick") return unknownActionStep("counter has no action '" + call.name + "'");
    ++counter_;
    if (!isEvaluationTwin()) --sharedPointer()->patience;
    StepResult r;
    r.consumedStep = true;
    return r;
  }
  StepResult idle() override { return idleStep("waited"); }

  int counter() const { return counter_; }
  int patience() const { return shared().patience; }

 private:
  friend class SimulatorBase<CounterSimulator, Person>;
  CounterSimulator(std::shared_ptr<Person> person, const SimulatorOptions& options, WorldRole role, std::uint64_t seed)
      : SimulatorBase(std::move(person), options, role) {
    reset(seed);
  }
  int counter_ = 0;
};

TEST(SimulatorBase, ATwinSharesTheUserButHasItsOwnWorldRngAndRole) {
  SimulatorOptions options;
  options.shiftEvery = 7;
  CounterSimulator training(options, 42);
  auto twinBase = training.makeEvaluationTwin();
  auto* twin = dynamic_cast<CounterSimulator*>(twinBase.get());
  ASSERT_NE(twin, nullptr);
  EXPECT_EQ(training.role(), WorldRole::Training);
  EXPECT_EQ(twin->role(), WorldRole::Evaluation);
  EXPECT_EQ(twin->options().shiftEvery, 7);

  CounterSimulator fromSeedZero(options, 0);
  EXPECT_EQ(twin->counter(), fromSeedZero.counter()) << "a twin starts reset with seed 0";

  const int before = training.counter();
  twin->act({"tick", {}});
  EXPECT_EQ(training.counter(), before) << "the twin's world is its own";
  EXPECT_EQ(training.patience(), 3) << "the twin never changes the shared user";
  training.act({"tick", {}});
  EXPECT_EQ(twin->patience(), 2) << "the twin sees the user as training left them";
}

TEST(SimulatorBase, StepBuildersSayWhatHappened) {
  CounterSimulator sim(SimulatorOptions{}, 1);
  const StepResult unknown = sim.act({"jump", {}});
  EXPECT_EQ(unknown.status, ActionStatus::UnknownAction);
  EXPECT_FALSE(unknown.consumedStep);
  EXPECT_EQ(unknown.message, "counter has no action 'jump'");
  const StepResult idle = sim.idle();
  EXPECT_EQ(idle.status, ActionStatus::Applied);
  EXPECT_TRUE(idle.consumedStep);
  EXPECT_EQ(idle.message, "waited");
}

}  // namespace
}  // namespace cbtl::sim
