// CookingSimulator: the DomainSimulator contract for Cooking — action names and argument kinds of cooking.cbtl,
// hand-written meal plans and their critiques, restocking, determinism, preference shifts shared with the
// evaluation twin, and unsatisfiable stock.
#include "domains/cooking/CookingSimulator.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <stdexcept>

namespace {

using namespace cbtl::domains::cooking;
using cbtl::sim::ActionCall;
using cbtl::sim::ActionStatus;
using cbtl::sim::FeedbackEvent;
using cbtl::sim::SimulatorOptions;
using cbtl::sim::StepResult;
using cbtl::sim::Value;

ActionCall movePot(const std::string& pot, double x, double y) {
  return ActionCall{"movePot", {Value::name(pot), Value::vec({x, y})}};
}
ActionCall addIngredient(const std::string& ing, const std::string& pot, double qty) {
  return ActionCall{"addIngredient", {Value::name(ing), Value::name(pot), Value::num(qty)}};
}
ActionCall endTick() { return ActionCall{"endTick", {}}; }
ActionCall serve(const std::string& meal) { return ActionCall{"serve", {Value::name(meal)}}; }

// Cooks seasoning the way cooking.cbtl's policy does: place two pots, add salt and pepper before tick
// `start`, run `total` ticks, serve. Served temperature: total - start - 1 ticks.
StepResult cookSeasoning(CookingSimulator& s, int start, int total, double qty = 0.97,
                         const std::string& meal = "seasoning") {
  EXPECT_EQ(s.act(movePot("pot0", 2.0, 2.0)).status, ActionStatus::Applied);
  EXPECT_EQ(s.act(movePot("pot2", 5.0, 5.0)).status, ActionStatus::Applied);
  for (int t = 0; t < total; ++t) {
    if (t == start) {
      EXPECT_EQ(s.act(addIngredient("salt", "pot0", qty)).status, ActionStatus::Applied);
      EXPECT_EQ(s.act(addIngredient("pepper", "pot2", qty)).status, ActionStatus::Applied);
    }
    const StepResult r = s.act(endTick());
    EXPECT_EQ(r.status, ActionStatus::Applied);
    EXPECT_TRUE(r.consumedStep);
  }
  return s.act(serve(meal));
}

const std::string& text(const FeedbackEvent& e, std::size_t i) { return e.args.at(i).text; }
double number(const FeedbackEvent& e, std::size_t i) { return e.args.at(i).number; }

TEST(CookingSimulator, ObservesStockByMemberName) {
  CookingSimulator s({}, 1);
  const auto obs = s.observe();
  EXPECT_EQ(obs.size(), 4u);
  for (const char* key : {"stock[salt]", "stock[pepper]", "stock[sugar]", "stock[flour]"}) {
    ASSERT_EQ(obs.count(key), 1u) << key;
    EXPECT_EQ(obs.at(key).kind, Value::Kind::Number);
    EXPECT_GE(obs.at(key).number, 10.0);
    EXPECT_LE(obs.at(key).number, 20.0);
  }
}

TEST(CookingSimulator, GoodPlanSatisfiesOnTwoConsecutiveMeals) {
  CookingSimulator s({}, 5);
  for (int meal = 0; meal < 2; ++meal) {
    const StepResult r = cookSeasoning(s, 0, 31);  // 31 - 0 - 1 = 30 ticks = 3.0
    EXPECT_EQ(r.status, ActionStatus::Applied);
    EXPECT_TRUE(r.consumedStep);
    EXPECT_TRUE(r.taskDone);
    ASSERT_TRUE(r.hasSatisfaction);
    EXPECT_EQ(r.satisfaction, 1.0) << r.message;
    ASSERT_EQ(r.feedback.size(), 2u);
    const char* expected[] = {"salt", "pepper"};  // pot order: pot0 then pot2
    for (std::size_t i = 0; i < 2; ++i) {
      const FeedbackEvent& e = r.feedback[i];
      EXPECT_EQ(e.name, "mealCritique");
      ASSERT_EQ(e.args.size(), 7u);
      EXPECT_EQ(text(e, 0), "seasoning");
      EXPECT_EQ(text(e, 1), expected[i]);
      EXPECT_EQ(number(e, 2), 0.0);
      EXPECT_EQ(number(e, 3), 31.0);
      EXPECT_EQ(number(e, 4), 0.97);
      EXPECT_EQ(text(e, 5), "tempGood");
      EXPECT_EQ(text(e, 6), "amountGood");
      EXPECT_EQ(e.args[5].kind, Value::Kind::Name);
      EXPECT_EQ(e.args[2].kind, Value::Kind::Number);
    }
  }
}

TEST(CookingSimulator, LateStartAlsoGivesThePlannedTemperature) {
  // Added before tick 4 and served after 35 ticks: 30 ticks, as cooking.cbtl's heatTicks(4, 35).
  CookingSimulator s({}, 9);
  const StepResult r = cookSeasoning(s, 4, 35);
  EXPECT_EQ(r.satisfaction, 1.0) << r.message;
  ASSERT_EQ(r.feedback.size(), 2u);
  EXPECT_EQ(number(r.feedback[0], 2), 4.0);
  EXPECT_EQ(number(r.feedback[0], 3), 35.0);
}

TEST(CookingSimulator, TemperatureBoundsAreExactInTicks) {
  struct Case {
    int total;
    const char* heat;
  };
  // Served ticks = total - 1: 27 hotter, 28 and 32 good, 33 colder.
  for (const Case c : {Case{28, "wantHotter"}, Case{29, "tempGood"}, Case{33, "tempGood"}, Case{34, "wantColder"}}) {
    CookingSimulator s({}, 2);
    const StepResult r = cookSeasoning(s, 0, c.total);
    ASSERT_EQ(r.feedback.size(), 2u);
    EXPECT_EQ(text(r.feedback[0], 5), c.heat) << c.total;
    EXPECT_EQ(r.satisfaction, std::string(c.heat) == "tempGood" ? 1.0 : -1.0);
  }
}

TEST(CookingSimulator, TooHotMealIsCritiquedColder) {
  CookingSimulator s({}, 3);
  const StepResult r = cookSeasoning(s, 0, 40);  // 39 ticks = 3.9 > 3.2
  EXPECT_EQ(r.satisfaction, -1.0);
  ASSERT_EQ(r.feedback.size(), 2u);
  for (const FeedbackEvent& e : r.feedback) {
    EXPECT_EQ(text(e, 5), "wantColder");
    EXPECT_EQ(text(e, 6), "amountGood");
  }
}

TEST(CookingSimulator, WrongAmountIsCritiqued) {
  CookingSimulator s({}, 3);
  StepResult r = cookSeasoning(s, 0, 31, 1.05);
  EXPECT_EQ(r.satisfaction, -1.0);
  ASSERT_EQ(r.feedback.size(), 2u);
  EXPECT_EQ(text(r.feedback[0], 6), "wantLess");
  r = cookSeasoning(s, 0, 31, 0.92);
  EXPECT_EQ(text(r.feedback[1], 6), "wantMore");
}

TEST(CookingSimulator, UnknownMealOrMissingIngredientIsUnsatisfying) {
  CookingSimulator s({}, 4);
  StepResult r = cookSeasoning(s, 0, 31, 0.97, "soup");
  EXPECT_EQ(r.satisfaction, -1.0);
  EXPECT_TRUE(r.feedback.empty());  // the user has no opinion on a meal they do not know
  EXPECT_TRUE(r.taskDone);

  // Only salt.
  ASSERT_EQ(s.act(movePot("pot0", 2.0, 2.0)).status, ActionStatus::Applied);
  ASSERT_EQ(s.act(addIngredient("salt", "pot0", 0.97)).status, ActionStatus::Applied);
  for (int t = 0; t < 31; ++t) s.act(endTick());
  r = s.act(serve("seasoning"));
  EXPECT_EQ(r.satisfaction, -1.0);
  ASSERT_EQ(r.feedback.size(), 1u);
  EXPECT_EQ(text(r.feedback[0], 5), "tempGood");

  // Nothing at all.
  r = s.act(serve("seasoning"));
  EXPECT_EQ(r.satisfaction, -1.0);
  EXPECT_TRUE(r.feedback.empty());
}

TEST(CookingSimulator, ServeRestocksAndResetsTheKitchen) {
  CookingSimulator s({}, 11);
  s.act(movePot("pot1", 5.0, 5.0));
  s.act(addIngredient("salt", "pot1", 1.0));
  s.act(endTick());
  s.act(endTick());
  const double saltBefore = s.world().stock(Ingredient::Salt);
  ASSERT_EQ(s.world().mealTicks(), 2);
  const StepResult r = s.act(serve("seasoning"));
  EXPECT_TRUE(r.taskDone);
  EXPECT_TRUE(r.consumedStep);
  for (const PotState& p : s.world().pots()) {
    EXPECT_FALSE(p.onStove);
    EXPECT_FALSE(p.ingredient.has_value());
    EXPECT_EQ(p.temperatureTicks, 0);
  }
  EXPECT_EQ(s.world().mealTicks(), 0);
  EXPECT_NE(s.world().stock(Ingredient::Salt), saltBefore);
  for (Ingredient i : kAllIngredients) {
    EXPECT_GE(s.world().stock(i), 10.0);
    EXPECT_LT(s.world().stock(i), 20.0);
  }
}

TEST(CookingSimulator, ServeDoesNotHeatAndDropsQueuedAdditions) {
  CookingSimulator s({}, 12);
  s.act(movePot("pot0", 2.0, 2.0));
  s.act(movePot("pot2", 5.0, 5.0));
  s.act(addIngredient("salt", "pot0", 0.97));
  s.act(addIngredient("pepper", "pot2", 0.97));
  for (int t = 0; t < 33; ++t) s.act(endTick());  // 32 ticks: the upper bound, good only if serving does not heat
  s.act(addIngredient("sugar", "pot1", 0.97));    // queued after the last tick: never reaches the meal
  const StepResult r = s.act(serve("seasoning"));
  EXPECT_EQ(r.satisfaction, 1.0) << r.message;
  EXPECT_EQ(r.feedback.size(), 2u);
}

TEST(CookingSimulator, MovePotRules) {
  CookingSimulator s({}, 13);
  StepResult r = s.act(movePot("pot1", 5.0, 5.0));
  EXPECT_EQ(r.status, ActionStatus::Applied);
  EXPECT_TRUE(r.consumedStep);
  r = s.act(movePot("pot0", 5.5, 5.5));
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  EXPECT_TRUE(r.consumedStep);
  EXPECT_FALSE(r.message.empty());
  r = s.act(movePot("pot3", 9.8, 5.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  EXPECT_TRUE(r.consumedStep);
  r = s.act(movePot("noPot", 2.0, 2.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  EXPECT_TRUE(r.consumedStep);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(s.stepCount(), 4);
  EXPECT_FALSE(s.world().pot(0).onStove);
  EXPECT_FALSE(s.world().pot(3).onStove);
  // A move is not a cooking tick.
  EXPECT_EQ(s.world().mealTicks(), 0);
}

TEST(CookingSimulator, AddIngredientRules) {
  CookingSimulator s({}, 14);
  const double salt = s.world().stock(Ingredient::Salt);
  StepResult r = s.act(addIngredient("salt", "pot0", 1.0));
  EXPECT_EQ(r.status, ActionStatus::Applied);
  EXPECT_FALSE(r.consumedStep);  // queued, no step
  EXPECT_EQ(s.stepCount(), 0);
  r = s.act(addIngredient("pepper", "pot0", 1.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);  // pot0 is about to be full
  s.act(endTick());
  EXPECT_EQ(s.world().stock(Ingredient::Salt), salt - 1.0);
  r = s.act(addIngredient("pepper", "pot0", 1.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);  // pot0 is full
  r = s.act(addIngredient("pepper", "pot1", 1000.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);  // more than the stock
  EXPECT_FALSE(r.message.empty());
  r = s.act(addIngredient("pepper", "noPot", 1.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  r = s.act(addIngredient("pepper", "pot1", -1.0));
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  s.act(endTick());
  EXPECT_FALSE(s.world().pot(1).ingredient.has_value());
}

TEST(CookingSimulator, IdleIsACookingTick) {
  CookingSimulator s({}, 15);
  s.act(movePot("pot0", 2.0, 2.0));
  s.act(addIngredient("salt", "pot0", 1.0));
  StepResult r = s.idle();
  EXPECT_TRUE(r.consumedStep);
  EXPECT_EQ(r.status, ActionStatus::Applied);
  EXPECT_EQ(s.world().pot(0).ingredient, Ingredient::Salt);
  s.idle();
  s.idle();
  EXPECT_EQ(s.world().pot(0).temperatureTicks, 2);
  EXPECT_EQ(s.world().mealTicks(), 3);
  EXPECT_EQ(s.stepCount(), 4);
}

TEST(CookingSimulator, UnknownActionsNeverCrash) {
  CookingSimulator s({}, 16);
  const auto obsBefore = s.observe();
  const std::vector<ActionCall> bad = {
      ActionCall{"fly", {}},
      ActionCall{"", {}},
      ActionCall{"movePot", {}},
      ActionCall{"movePot", {Value::num(1), Value::vec({2, 2})}},
      ActionCall{"movePot", {Value::name("pot0"), Value::num(2)}},
      ActionCall{"movePot", {Value::name("pot0"), Value::vec({2, 2, 0})}},
      ActionCall{"movePot", {Value::name("pot9"), Value::vec({2, 2})}},
      ActionCall{"addIngredient", {Value::name("salt"), Value::name("pot0")}},
      ActionCall{"addIngredient", {Value::name("salt"), Value::name("pot0"), Value::name("lots")}},
      ActionCall{"addIngredient", {Value::name("saffron"), Value::name("pot0"), Value::num(1)}},
      ActionCall{"addIngredient", {Value::num(0), Value::name("pot0"), Value::num(1)}},
      ActionCall{"endTick", {Value::num(1)}},
      ActionCall{"serve", {}},
      ActionCall{"serve", {Value::num(3)}},
  };
  for (const ActionCall& call : bad) {
    const StepResult r = s.act(call);
    EXPECT_EQ(r.status, ActionStatus::UnknownAction) << call.name;
    EXPECT_FALSE(r.consumedStep) << call.name;
    EXPECT_FALSE(r.taskDone) << call.name;
    EXPECT_FALSE(r.message.empty()) << call.name;
  }
  EXPECT_EQ(s.stepCount(), 0);
  EXPECT_EQ(s.world().mealTicks(), 0);
  EXPECT_TRUE(s.world().queuedAdditions().empty());
  EXPECT_EQ(s.observe().at("stock[salt]").number, obsBefore.at("stock[salt]").number);
}

TEST(CookingSimulator, SameSeedSameStock) {
  CookingSimulator a({}, 42), b({}, 42), c({}, 43);
  EXPECT_EQ(a.world().stock(), b.world().stock());
  EXPECT_NE(a.world().stock(), c.world().stock());
  // The stock is the documented draw: U(10, 20) from the raw mt19937_64 words, salt first.
  std::mt19937_64 raw(42);
  for (Ingredient i : kAllIngredients) {
    EXPECT_EQ(a.world().stock(i), 10.0 + 10.0 * (static_cast<double>(raw() >> 11) * 0x1.0p-53));
  }
  // reset(seed) draws the same kitchen again, whatever happened before.
  const Stock first = a.world().stock();
  cookSeasoning(a, 0, 31);
  a.reset(42);
  EXPECT_EQ(a.world().stock(), first);
  // The n-th restock after a serve is reproducible too.
  cookSeasoning(b, 0, 31);
  cookSeasoning(a, 0, 31);
  EXPECT_EQ(a.world().stock(), b.world().stock());
}

TEST(CookingSimulator, InvalidOptionsThrow) {
  SimulatorOptions o;
  o.shiftEvery = -1;
  EXPECT_THROW(CookingSimulator(o, 1), std::invalid_argument);
  o = {};
  o.shiftLo = 1.2;
  o.shiftHi = 1.1;
  EXPECT_THROW(CookingSimulator(o, 1), std::invalid_argument);
  o = {};
  o.unsatisfiableStockProbability = 1.5;
  EXPECT_THROW(CookingSimulator(o, 1), std::invalid_argument);
}

TEST(CookingSimulator, ShiftEveryNStepsIsAnnouncedAndSharedWithTheTwin) {
  SimulatorOptions o;
  o.shiftEvery = 5;
  o.shiftLo = 2.0;  // a fixed factor makes the new ranges exact
  o.shiftHi = 2.0;
  o.announceShifts = true;
  CookingSimulator s(o, 21);
  auto twinBase = s.makeEvaluationTwin();
  auto* twin = dynamic_cast<CookingSimulator*>(twinBase.get());
  ASSERT_NE(twin, nullptr);
  EXPECT_FALSE(twin->shiftsUser());
  EXPECT_EQ(&twin->user(), &s.user());

  // A queued addition is not a step; moves and ticks are.
  s.act(addIngredient("salt", "pot0", 1.0));
  for (int step = 1; step <= 4; ++step) {
    const StepResult r = s.idle();
    EXPECT_FALSE(r.preferencesChanged) << step;
  }
  EXPECT_EQ(s.user().shiftCount(), 0);
  StepResult r = s.act(movePot("pot1", 5.0, 5.0));
  EXPECT_TRUE(r.preferencesChanged);
  EXPECT_EQ(s.user().shiftCount(), 1);
  const IngredientTaste& salt = s.user().meal("seasoning")->ingredients.at(Ingredient::Salt);
  EXPECT_DOUBLE_EQ(salt.temperature.lo, 5.8);
  EXPECT_DOUBLE_EQ(salt.temperature.hi, 6.2);
  EXPECT_DOUBLE_EQ(salt.quantity.lo, 1.925);
  EXPECT_DOUBLE_EQ(salt.quantity.hi, 1.975);

  // The twin sees the shifted user: the meal that pleased the original user now wants more and hotter.
  twin->reset(100);
  r = cookSeasoning(*twin, 0, 31);
  EXPECT_EQ(r.satisfaction, -1.0);
  ASSERT_EQ(r.feedback.size(), 2u);
  EXPECT_EQ(text(r.feedback[0], 5), "wantHotter");
  EXPECT_EQ(text(r.feedback[0], 6), "wantMore");
  // ... and never shifts the user itself, however many steps it takes.
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(twin->idle().preferencesChanged);
  EXPECT_EQ(s.user().shiftCount(), 1);

  // The next shift comes 5 steps later; reset does not restart the count.
  s.reset(7);
  for (int step = 6; step <= 9; ++step) EXPECT_FALSE(s.idle().preferencesChanged);
  EXPECT_TRUE(s.idle().preferencesChanged);
  EXPECT_EQ(s.user().shiftCount(), 2);
}

TEST(CookingSimulator, UnannouncedShiftStillShifts) {
  SimulatorOptions o;
  o.shiftEvery = 3;
  CookingSimulator s(o, 22);
  const IngredientTaste before = s.user().meal("seasoning")->ingredients.at(Ingredient::Pepper);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(s.idle().preferencesChanged);
  EXPECT_EQ(s.user().shiftCount(), 1);
  const IngredientTaste after = s.user().meal("seasoning")->ingredients.at(Ingredient::Pepper);
  EXPECT_NE(after.temperature.lo, before.temperature.lo);
  EXPECT_NE(after.quantity.lo, before.quantity.lo);
  // Factors in [0.9, 1.1]: the centre moves by at most 10%.
  EXPECT_NEAR(after.temperature.centre(), 3.0, 0.3 + 1e-9);
  EXPECT_NEAR(after.quantity.centre(), 0.975, 0.0975 + 1e-9);
}

TEST(CookingSimulator, ShiftsDependOnlyOnTheSeedNotOnTheActions) {
  SimulatorOptions o;
  o.shiftEvery = 40;
  CookingSimulator a(o, 23), b(o, 23);
  cookSeasoning(a, 0, 37);                // 2 moves + 37 ticks + serve = 40 steps, two restocks' worth of draws
  for (int i = 0; i < 40; ++i) b.idle();  // no serve, fewer world draws
  ASSERT_EQ(a.user().shiftCount(), 1);
  ASSERT_EQ(b.user().shiftCount(), 1);
  EXPECT_EQ(a.user().meal("seasoning")->ingredients.at(Ingredient::Salt).temperature.lo,
            b.user().meal("seasoning")->ingredients.at(Ingredient::Salt).temperature.lo);
}

TEST(CookingSimulator, UnsatisfiableStockLeavesOneRequiredIngredientShort) {
  SimulatorOptions o;
  o.unsatisfiableStockProbability = 1.0;
  std::set<Ingredient> picked;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    CookingSimulator s(o, seed);
    for (int meal = 0; meal < 2; ++meal) {  // at reset, then after a serve
      int shortCount = 0;
      for (Ingredient i : kAllIngredients) {
        const double stock = s.world().stock(i);
        if (stock < 10.0) {
          ++shortCount;
          picked.insert(i);
          EXPECT_TRUE(i == Ingredient::Salt || i == Ingredient::Pepper);
          EXPECT_GE(stock, 0.9);
          EXPECT_LT(stock, 0.95);  // the user's minimum
        }
      }
      EXPECT_EQ(shortCount, 1) << seed;
      const StepResult r = cookSeasoning(s, 0, 31, 0.9);  // the spec's minimum: always within the stock
      EXPECT_EQ(r.satisfaction, -1.0);
    }
  }
  EXPECT_EQ(picked.size(), 2u);  // both salt and pepper get picked over 80 restocks
}

TEST(CookingSimulator, UnsatisfiableStockFollowsTheShiftedUserAndFloorsAtTheSpec) {
  // A user whose minimum is below the spec's 0.9: the stock is set to exactly 0.9.
  const IngredientTaste lenient{Range{2.8, 3.2}, Range{0.5, 0.8}};
  CookingUser user({MealTaste{"seasoning", {{Ingredient::Salt, lenient}}}});
  SimulatorOptions o;
  o.unsatisfiableStockProbability = 1.0;
  CookingSimulator s(o, 31, user);
  EXPECT_EQ(s.world().stock(Ingredient::Salt), 0.9);
  // The twin restocks with the same rule.
  auto twin = s.makeEvaluationTwin();
  twin->reset(5);
  EXPECT_EQ(twin->observe().at("stock[salt]").number, 0.9);
}

TEST(CookingSimulator, ZeroProbabilityNeverShortens) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    CookingSimulator s({}, seed);
    for (Ingredient i : kAllIngredients) EXPECT_GE(s.world().stock(i), 10.0);
  }
}

TEST(CookingSimulator, TwinHasItsOwnWorld) {
  CookingSimulator s({}, 50);
  auto twin = s.makeEvaluationTwin();
  twin->reset(50);
  EXPECT_EQ(twin->observe().at("stock[salt]").number, s.world().stock(Ingredient::Salt));
  twin->act(movePot("pot0", 2.0, 2.0));
  EXPECT_FALSE(s.world().pot(0).onStove);
  EXPECT_EQ(s.stepCount(), 0);
}

}  // namespace
