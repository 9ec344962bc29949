// The Feeding simulator's meals and answers: a new meal (food, sauces, setting) with every request cycle and the
// same meal within one, the observations a CSP reads, the hidden user's ideals per food and setting, and a bite's
// answers: the dip, signal and verbosity answers, the other choices turned down, and each preference judged.
#include "domains/feeding/FeedingSimulator.h"

#include "robot/world/Support.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace {

using cbtl::domains::feeding::FeedingSimulator;
using cbtl::domains::feeding::FeedingUser;
using cbtl::domains::feeding::foodEntry;
using cbtl::domains::feeding::Request;
using cbtl::sim::ActionCall;
using cbtl::sim::StepResult;
using cbtl::sim::Value;

const cbtl::domains::ProgramFacts& feeding() { return cbtl::test::programFacts("feeding"); }

struct Meal {
  std::string food, setting;
  std::vector<std::string> dips;
  bool operator==(const Meal&) const = default;
};
Meal mealOf(const FeedingSimulator& sim) { return Meal{sim.food(), sim.setting(), sim.dipsOnTable()}; }

// Ends the current request the way the caregiver ends a failed one (an unknown sauce fails it), so the test can
// step through the request cycle without planning.
void endRequest(FeedingSimulator& sim) {
  const StepResult r = sim.act(ActionCall{"dipInto", {Value::name("mustard")}});
  ASSERT_TRUE(r.taskDone);
}

TEST(FeedingSimulator, EveryRequestCycleIsANewMealAndAMealLastsItsCycle) {
  std::set<std::string> foods, settings;
  int changes = 0;
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    FeedingSimulator sim(feeding(), {}, seed);
    Meal meal = mealOf(sim);
    for (int request = 0; request < 12; ++request) {
      foods.insert(sim.food());
      settings.insert(sim.setting());
      const bool cycleEnds = sim.request() == Request::Drink;
      endRequest(sim);
      if (cycleEnds) {
        changes += mealOf(sim) == meal ? 0 : 1;
        meal = mealOf(sim);
      } else {
        EXPECT_EQ(mealOf(sim), meal) << "seed " << seed << " request " << request << ": the meal changed mid-cycle";
      }
    }
  }
  EXPECT_EQ(foods,
            (std::set<std::string>{"french fries", "raw vegetables", "potato wedges", "carrot sticks", "tater tots"}));
  EXPECT_EQ(settings, (std::set<std::string>{"alone", "withFriend", "withTv", "withFriendAndTv"}));
  EXPECT_GT(changes, 20);  // of 30 cycle ends, a few may draw the same meal again
}

// Which table stands at the table's place (the other is parked 3 m below it).
std::string tableInUse(const FeedingSimulator& sim) {
  const auto& f = sim.worldState()->fixtures;
  return f.at("table_round").position.z() > f.at("table").position.z() ? "circular" : "rectangular";
}

bool plateStands(FeedingSimulator& sim) {
  auto& ws = sim.world().workspace();
  return cbtl::world::supportAt(ws, "plate", *ws.objectPose("plate")).supported();
}

TEST(FeedingSimulator, MealsComeAtBothTablesAndThePlateAlwaysStandsOnTheTableInUse) {
  std::set<std::string> tables;
  for (std::uint64_t seed = 0; seed < 10; ++seed) {
    FeedingSimulator sim(feeding(), {}, seed);
    for (int request = 0; request < 12; ++request) {
      EXPECT_EQ(sim.meal().table, tableInUse(sim)) << "seed " << seed << " request " << request;
      EXPECT_TRUE(plateStands(sim)) << "seed " << seed << " request " << request;
      tables.insert(sim.meal().table);
      endRequest(sim);
    }
  }
  EXPECT_EQ(tables, (std::set<std::string>{"rectangular", "circular"}));
}

TEST(FeedingSimulator, AScriptedMealPutsItsTableInPlaceAndThePlateBackOnIt) {
  FeedingSimulator sim(feeding(), {}, 3);
  sim.serveMealNow(cbtl::domains::feeding::paperMeals()[0]);
  ASSERT_EQ(tableInUse(sim), "rectangular");
  ASSERT_TRUE(sim.placeOnTable("plate", 0.30, 0.25));  // a corner of the plate's area: off the round table
  sim.serveMealNow(cbtl::domains::feeding::paperMeals()[1]);
  EXPECT_EQ(tableInUse(sim), "circular");
  EXPECT_TRUE(plateStands(sim));
  EXPECT_NE(sim.worldState()->objects.at("plate").position.y(), 0.25);
  const auto plate = sim.worldState()->objects.at("plate").position;
  EXPECT_FALSE(sim.placeOnTable("plate", 0.30, 0.25));  // refused, nothing moves
  EXPECT_EQ(sim.worldState()->objects.at("plate").position, plate);
  EXPECT_TRUE(sim.placeOnTable("plate", 0.35, 0.45));
}

// The friend and the TV the setting names are in the room (at the height the scene gives them, z = 0); the others
// are parked under the floor. Pictures show them; nothing the robot may do depends on them (class visual).
TEST(FeedingSimulator, TheSettingsFriendAndTvAreInTheRoomAndTheOthersAway) {
  FeedingSimulator sim(feeding(), {}, 3);
  auto present = [&](const char* fixture) { return sim.worldState()->fixtures.at(fixture).position.z() > -1.0; };
  for (const auto& meal : cbtl::domains::feeding::paperMeals()) {
    sim.serveMealNow(meal);
    const bool withFriend = meal.setting == "withFriend" || meal.setting == "withFriendAndTv";
    const bool withTv = meal.setting == "withTv" || meal.setting == "withFriendAndTv";
    EXPECT_EQ(present("friend"), withFriend) << meal.setting;
    EXPECT_EQ(present("tv"), withTv) << meal.setting;
  }
  // Drawn meals too: every setting shows its company.
  std::set<std::string> seen;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    sim.reset(seed);
    const std::string& setting = sim.setting();
    seen.insert(setting);
    EXPECT_EQ(present("friend"), setting == "withFriend" || setting == "withFriendAndTv") << setting;
    EXPECT_EQ(present("tv"), setting == "withTv" || setting == "withFriendAndTv") << setting;
  }
  EXPECT_EQ(seen.size(), 4U);
}

TEST(FeedingSimulator, TheTableAreasAreTheProgramsConstants) {
  const cbtl::domains::ProgramFacts& facts = feeding();
  const auto areas = cbtl::domains::feeding::TableAreas::of(facts);
  EXPECT_EQ(areas.plate.x0, 0.30);  // feeding.cbtl: const plateX0 = 0.30;
  EXPECT_GT(facts.numbers.at("plateX0").span.line, 0u);
  EXPECT_EQ(areas.plate.y1, 0.64);
  EXPECT_EQ(areas.drink.y0, 0.15);
  cbtl::domains::ProgramFacts without = facts;
  without.numbers.erase("drinkY1");
  try {
    FeedingSimulator sim(without, {}, 0);
    ADD_FAILURE() << "a program without drinkY1 was accepted";
  } catch (const cbtl::rt::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("drinkY1"), std::string::npos) << e.what();
  }
  cbtl::domains::ProgramFacts inverted = facts;
  inverted.numbers["plateX0"].value = 0.5;  // beyond plateX1 = 0.38
  try {
    cbtl::domains::feeding::TableAreas::of(inverted);
    ADD_FAILURE() << "an empty plate area was accepted";
  } catch (const cbtl::rt::RuntimeError& e) {
    EXPECT_NE(e.location.find("feeding.cbtl:"), std::string::npos) << e.what();  // where plateX0 is declared
  }
}

TEST(FeedingSimulator, ObservesTheMealAndItsSetting) {
  FeedingSimulator sim(feeding(), {}, 4);
  const auto o = sim.observe();
  EXPECT_EQ(o.at("foodOnPlate").text, foodEntry(sim.food()));
  EXPECT_EQ(o.at("mealSetting").text, sim.setting());
  EXPECT_EQ(o.at("dipsOnTable").members, sim.dipsOnTable());
  std::vector<std::string> choices = sim.dipsOnTable();
  choices.push_back("noDip");
  EXPECT_EQ(o.at("dipChoices").members, choices);
}

TEST(FeedingUser, IdealsDependOnTheFoodTheSauceOnTheTableAndTheSetting) {
  const FeedingUser u = FeedingUser::paperDefault();
  EXPECT_EQ(u.idealDip("french fries", "alone", {"bbqSauce", "ketchup"}), "ketchup");
  EXPECT_EQ(u.idealDip("french fries", "alone", {"bbqSauce", "ranch"}), "ranch");  // the second choice
  EXPECT_EQ(u.idealDip("french fries", "alone", {"bbqSauce", "hummus"}), "noDip");
  EXPECT_EQ(u.idealDip("raw vegetables", "withTv", {"hummus", "ranch"}), "ranch");
  FeedingUser tidy = u;
  tidy.dipRankingInSetting = {{"french fries|withFriend", {}}};  // nothing messy with a friend
  EXPECT_EQ(tidy.idealDip("french fries", "withFriend", {"ketchup", "ranch"}), "noDip");
  EXPECT_EQ(tidy.idealDip("french fries", "alone", {"ketchup", "ranch"}), "ketchup");
  EXPECT_EQ(u.idealVerbosity("alone"), "brief");
  EXPECT_EQ(u.idealVerbosity("withFriend"), "silent");
  EXPECT_EQ(u.idealVerbosity("withFriendAndTv"), "silent");
  EXPECT_EQ(u.idealSignal("withTv"), "button");
}

// A bite, from the simulator's side: the plan's actions as a solved feedBite would send them, with the arm moves
// left out (they need a motion plan; the answers do not depend on them).
TEST(FeedingSimulator, ABiteIsAnsweredAndEachPreferenceJudged) {
  int bites = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    FeedingSimulator sim(feeding(), {}, seed);
    if (sim.request() != Request::Food) continue;
    const std::string food = sim.food();
    const std::string ideal = sim.user().idealDip(food, sim.setting(), sim.dipsOnTable());
    const std::string offered = sim.dipsOnTable().front();
    const std::map<std::string, std::string> sauceNames = {
        {"ketchup", "ketchup"}, {"bbqSauce", "BBQ sauce"}, {"ranch", "ranch dressing"}, {"hummus", "hummus"}};
    ASSERT_FALSE(sim.act(ActionCall{"dipInto", {Value::name(sauceNames.at(offered))}}).taskDone);
    sim.act(ActionCall{"say", {Value::name("Ready when you are.")}});
    sim.act(ActionCall{"waitForReady", {Value::name("button")}});
    sim.act(ActionCall{"waitForUser", {Value::name("biteTaken")}});
    const StepResult r = sim.act(ActionCall{"waitForUser", {Value::name("done")}});
    ASSERT_TRUE(r.taskDone) << r.message;
    std::map<std::string, std::vector<Value>> said;
    std::vector<std::string> turnedDown;
    std::map<std::string, std::vector<std::string>> notWanted;  // signal / verbosity members turned down
    for (const auto& f : r.feedback) {
      if (f.name == "dipNotWanted") {
        EXPECT_EQ(f.args[0].text, foodEntry(food));
        turnedDown.push_back(f.args[1].text);
      } else if (f.name == "signalNotWanted" || f.name == "verbosityNotWanted") {
        ASSERT_EQ(f.args.size(), 1u);
        notWanted[f.name].push_back(f.args[0].text);
      } else {
        said[f.name] = f.args;
      }
    }
    ASSERT_EQ(said.count("dipAnswer"), 1u);
    EXPECT_EQ(said["dipAnswer"][1].text, offered);
    EXPECT_EQ(said["dipAnswer"][2].text, ideal);
    // Every choice of the meal is accounted for once: offered, ideal, or turned down.
    std::vector<std::string> accounted = turnedDown;
    accounted.push_back(offered);
    if (ideal != offered) accounted.push_back(ideal);
    std::sort(accounted.begin(), accounted.end());
    std::vector<std::string> choices = sim.dipsOnTable();
    choices.push_back("noDip");
    std::sort(choices.begin(), choices.end());
    EXPECT_EQ(accounted, choices) << "seed " << seed;
    // Likewise every ready signal and every verbosity: offered, ideal, or turned down, each once.
    const auto accountsForEvery = [&](const std::string& answer, const std::string& turnedDownEvent,
                                      std::vector<std::string> members) {
      std::vector<std::string> seen = notWanted[turnedDownEvent];
      seen.push_back(said[answer][0].text);
      if (said[answer][1].text != said[answer][0].text) seen.push_back(said[answer][1].text);
      std::sort(seen.begin(), seen.end());
      std::sort(members.begin(), members.end());
      EXPECT_EQ(seen, members) << answer << ", seed " << seed;
    };
    accountsForEvery("signalAnswer", "signalNotWanted", FeedingUser::readySignals());
    accountsForEvery("verbosityAnswer", "verbosityNotWanted", FeedingUser::verbosities());
    std::map<std::string, bool> judged(r.preferences.begin(), r.preferences.end());
    EXPECT_EQ(judged.size(), 5u);
    EXPECT_EQ(judged["dip"], offered == ideal);
    EXPECT_EQ(judged["signal"], true);
    EXPECT_EQ(judged["verbosity"], sim.user().idealVerbosity(sim.setting()) == "brief");
    EXPECT_EQ(judged["bite"], judged["dip"] && judged["signal"] && judged["verbosity"] && judged["view"]);
    EXPECT_EQ(r.satisfaction, judged["bite"] ? 1.0 : -1.0);
    ++bites;
  }
  EXPECT_GT(bites, 5);
}

}  // namespace

namespace {

TEST(FeedingUser, ParticipantsAreReproducibleAndDiverse) {
  std::set<std::string> signals, verbosities, friesRankings;
  int noDipWithAFriend = 0;
  for (std::uint64_t n = 0; n < 60; ++n) {
    const FeedingUser a = FeedingUser::participant(n), b = FeedingUser::participant(n);
    EXPECT_EQ(a.occlusionThreshold, b.occlusionThreshold);
    EXPECT_EQ(a.dipRanking, b.dipRanking);
    EXPECT_EQ(a.dipRankingInSetting, b.dipRankingInSetting);
    EXPECT_EQ(a.readySignal, b.readySignal);
    EXPECT_EQ(a.verbosityInSetting, b.verbosityInSetting);
    EXPECT_GE(a.occlusionThreshold, 0.02);
    EXPECT_LE(a.occlusionThreshold, 0.08);
    EXPECT_EQ(a.dipRanking.size(), 5u);
    signals.insert(a.idealSignal("withTv"));
    verbosities.insert(a.idealVerbosity("withFriend"));
    std::string fries;
    for (const auto& d : a.dipRanking.at("french fries")) fries += d + ",";
    friesRankings.insert(fries);
    noDipWithAFriend += a.idealDip("french fries", "withFriend", {"bbqSauce", "hummus", "ketchup", "ranch"}) == "noDip";
  }
  EXPECT_EQ(signals.size(), 3u);
  EXPECT_EQ(verbosities.size(), 3u);
  EXPECT_GT(friesRankings.size(), 8u);
  EXPECT_GT(noDipWithAFriend, 5);
  EXPECT_LT(noDipWithAFriend, 40);
  EXPECT_NE(FeedingUser::participant(0).dipRanking, FeedingUser::participant(1).dipRanking);
}

// A participant's dip with one food mostly says which they want with another of its kind, and nothing about a
// food of the other kind (FeedingUser::participant).
TEST(FeedingUser, ParticipantsTakeTheSameDipWithFoodsOfOneKind) {
  int friesAndTots = 0, friesAndCarrots = 0;
  for (std::uint64_t n = 0; n < 200; ++n) {
    const FeedingUser u = FeedingUser::participant(n);
    const std::vector<std::string> potatoSauces = {"bbqSauce", "ketchup"};
    friesAndTots +=
        u.idealDip("french fries", "alone", potatoSauces) == u.idealDip("tater tots", "alone", potatoSauces);
    friesAndCarrots += u.dipRanking.at("french fries") == u.dipRanking.at("carrot sticks");
  }
  // Same ranking with probability (1 - 0.25)^2 plus chance agreement; the kinds are drawn apart.
  EXPECT_GT(friesAndTots, 120);
  EXPECT_LT(friesAndCarrots, 60);
}

TEST(FeedingSimulator, AParticipantReplacesTheDefaultUser) {
  cbtl::sim::SimulatorOptions options;
  options.participant = 7;
  FeedingSimulator sim(feeding(), options, 0);
  EXPECT_EQ(sim.user().dipRanking, FeedingUser::participant(7).dipRanking);
  EXPECT_EQ(sim.makeEvaluationTwin() != nullptr, true);
  FeedingSimulator standard(feeding(), {}, 0);
  EXPECT_EQ(standard.user().dipRanking, FeedingUser::paperDefault().dipRanking);
}

}  // namespace

namespace {

// On 2026-12-03 a 5,000-step run of Feeding (No Personalization, seed 4) was stuck from step 2,692 on: the drink
// came back from a hand-over tilted, the caregiver put it on the table that way, and every moveDrink and
// movePlate of the prepare request was blocked by the tilted cup touching the table top. The caregiver stands
// the drink upright.
TEST(FeedingSimulator, TheCaregiverPutsTheDrinkOnTheTableUpright) {
  FeedingSimulator sim(feeding(), {}, 4);
  const auto upright = sim.worldState()->objects.at("drink").orientation;
  for (int request = 0; request < 4 && sim.request() != Request::Drink; ++request) endRequest(sim);
  ASSERT_EQ(sim.request(), Request::Drink);
  // The user hands the drink back tilted; the request ends as a served one (a failed one restores the scene).
  auto& ws = sim.world().workspace();
  auto drink = *ws.objectPose("drink");
  drink.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitX())) * drink.orientation;
  ws.setObjectPose("drink", drink);
  sim.act(ActionCall{"waitForUser", {Value::name("done")}});
  ASSERT_TRUE(sim.act(ActionCall{"moveArmToNamed", {Value::name("retract")}}).taskDone);
  for (int bite = 0; bite < 2; ++bite) {  // two bites, served without a failed action
    ASSERT_EQ(sim.request(), Request::Food);
    sim.act(ActionCall{"waitForUser", {Value::name("biteTaken")}});
    ASSERT_TRUE(sim.act(ActionCall{"waitForUser", {Value::name("done")}}).taskDone);
  }
  ASSERT_EQ(sim.request(), Request::Prepare);
  EXPECT_TRUE(sim.worldState()->objects.at("drink").orientation.isApprox(upright));
  const auto plate = sim.worldState()->objects.at("plate").position;
  const double y = plate.y() > 0.45 ? 0.2 : 0.7;  // a spot of the drink's domain well away from the plate
  const StepResult moved = sim.act(ActionCall{"moveDrink", {Value::vec({0.34, y})}});
  EXPECT_TRUE(moved.taskDone) << moved.message;
  EXPECT_EQ(moved.satisfaction, 1.0) << moved.message;
}

}  // namespace
