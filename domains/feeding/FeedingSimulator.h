// FeedingSimulator.h — the Feeding domain (domains/feeding/feeding.cbtl) behind the runtime's DomainSimulator
// contract: the Gen3 on its stand in feeding.xml, the plate, the drink and the utensil, and a hidden
// FeedingUser who eats, drinks and answers questions.
//
// Requests cycle with period 4, as in the reference: food, food, prepare (the drink appears on the table at a
// random spot clear of the plate, standing on the table), drink. Each cycle is one meal: when it starts again, a
// new meal is served (the food, two of the four sauces, the setting and the table's shape, drawn anew; the paper's
// five meals changed food, sauces, company and table too; a plate that would not stand on the new table is put at
// a random spot where it does). requestedTask() names the .cbtl task of the current request:
// feedBite, prepareDrink, giveDrink. A request ends (taskDone, satisfaction +1 or -1) when
//   feedBite:     waitForUser("done") after waitForUser("biteTaken"); the user answers dipAnswer(food, offered
//                 dip, ideal dip), dipNotWanted(food, choice) for every other choice of the meal (dipChoices)
//                 that was neither offered nor the ideal, signalAnswer(offered, ideal) and
//                 verbosityAnswer(perceived, ideal) (the ideals for this food and setting), with
//                 signalNotWanted(s) and verbosityNotWanted(v) for every other member, and is satisfied
//                 (+1) iff all three match and their view was never blocked during the bite; the step reports
//                 each of the four preferences (view, dip, signal, verbosity) and bite (all four met), and the
//                 measure userClearance: the smallest distance between the robot (with the utensil it holds)
//                 and the user's body and head at every waypoint of every path the request executed (capped at
//                 0.5 m; robot/world/RobotDistance.h) and userKeepOutSlack, the smallest margin left to the
//                 keep-out distance feeding.xml declares for that pair (2 cm, 5 mm for the fork near the head);
//   prepareDrink: moveDrink succeeds (+1);
//   giveDrink:    the arm is back at a named configuration, empty-handed, after waitForUser("done") (+1 iff
//                 the view was never blocked during the request; the step reports view, userClearance and
//                 userKeepOutSlack);
// and as a failure (-1) when any action fails (no IK, no path, a grasp out of reach, ...): the caregiver then
// puts the utensil back, opens the gripper and folds the arm to `retract`.
// View feedback: after every successful moveArm(q) (the configurations the CSP chose), the user says
// viewBlocked(q) when the occlusion score from their eyes (Occlusion.h) reaches their threshold, else the
// move passes as viewClear(q).
//
// Actions: the standard ones through actions::RobotActions (one step each), Feeding's movePlate(xy) and
// moveDrink(xy) (TableSlide.h, one step each), with three Feeding rules: grasp("drink")
// moves the tool in front of the drink's handle (kDrinkGraspOffset from the drink's body frame, 10 cm short
// of it along -y, tool z along +y; nearer, the open fingers touch it), attaches the drink, closes and lifts 1 cm;
// release() of the utensil at its mount puts it back in the mount (the mount is not a surface), and the
// domain's own actions dipInto(sauce: text), acquireFood() (the tool must be within 0.1 m of the plate centre
// horizontally, holding the utensil) and waitForReady(signal: ReadySignal), one step each.
// Observations: plateXY, drinkXY (vec<2>), dipsOnTable (set of Dip entries), dipChoices (the same and noDip: what
// the robot may offer), foodOnPlate (Food entry), mealSetting (MealSetting member).
//
// Determinism: reset(seed) reseeds the simulator's world::Rng; the episode draws, in order, the plate
// position, the position in the request cycle, the meal (food, the two dips on the table, setting, table, and the
// plate's new spot if it must move), and after
// that, request by request, a prepare request's drink position and each new cycle's meal. Of SimulatorOptions
// only `participant` applies (preference shifts and unsatisfiable stock do not).
#pragma once

#include "domains/ProgramFacts.h"
#include "domains/feeding/FeedingUser.h"
#include "robot/actions/RobotSimulator.h"
#include "runtime/sim/SimulatorBase.h"

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::domains::feeding {

enum class Request { Food, Prepare, Drink };
const char* toString(Request r);

// One meal: the food on the plate, the two sauces on the table (Dip entries, sorted), the setting (MealSetting
// member) and the table's shape: "rectangular" or "circular", feeding.xml's fixtures table and table_round (the
// one in use stands where the scene puts "table", the other is parked under the floor).
struct Meal {
  std::string food;
  std::vector<std::string> dips;
  std::string setting;
  std::string table;
  bool operator==(const Meal&) const = default;
};
// The paper's five meals of its web study, in order: 1 alone, rectangular table, french fries, ketchup and BBQ
// sauce; 2 with a friend, circular, raw vegetables, ranch and hummus; 3 with the TV on, circular, potato
// wedges, ketchup and BBQ; 4 alone, circular, carrot sticks, ranch and hummus; 5 with a friend and the TV,
// rectangular, tater tots, ketchup and BBQ.
const std::vector<Meal>& paperMeals();

// Where the caregiver puts the plate and the drink on the table when the simulator draws a spot (the plate an
// episode starts with, the plate moved for a new table, a prepare request's drink): the program's constants
// plateX0 .. plateY1 and drinkX0 .. drinkY1 (feeding.cbtl's variable domains), metres in the world frame.
struct TableAreas {
  struct Box {
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  };
  Box plate, drink;
  // Throws rt::RuntimeError naming the first constant the program does not declare, or an area that is empty
  // (x0 > x1 or y0 > y1) or not finite (at its first constant's declaration).
  static TableAreas of(const ProgramFacts& program);
};

// What a training world shares with its evaluation twins.
struct FeedingShared {
  std::shared_ptr<const world::Scene> scene;
  FeedingUser user;
  TableAreas areas;
};

// The step loop is actions::RobotSimulator's (no caregiver steps in when the robot idles: a request simply waits);
// the evaluation twin is sim::SimulatorBase's (it shares the user; its own world and RNG, reset with seed 0 until the
// caller resets it).
class FeedingSimulator final
    : public sim::SimulatorBase<FeedingSimulator, const FeedingShared, actions::RobotSimulator> {
 public:
  // The paper's user (FeedingUser::paperDefault), or participant `options.participant` when it is >= 0
  // (FeedingUser::participant), in the program's scene (feeding.xml). Throws
  // std::invalid_argument when `program` names no scene, rt::RuntimeError when it lacks a constant of TableAreas
  // (or its area is empty), std::runtime_error when the scene cannot be loaded.
  FeedingSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed);
  FeedingSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed,
                   FeedingUser user);

  void reset(std::uint64_t seed) override;
  sim::Observation observe() const override;
  std::string requestedTask() const override;
  // bite (every preference of a bite met), view, dip, signal, verbosity
  std::vector<std::string> judgedPreferences() const override;

  Request request() const { return request_; }
  const std::string& food() const { return food_; }
  const std::vector<std::string>& dipsOnTable() const { return dips_; }
  const std::string& setting() const { return setting_; }
  Meal meal() const { return Meal{food_, dips_, setting_, table_}; }

  // Scripted episodes (the study's meals, the demonstration): serves `meal` now (its table in place, the plate
  // moved to a random spot of it if it would not stand where it is) and makes the current request the first
  // bite of its cycle (food, food, prepare, drink), the drink off the table.
  void serveMealNow(const Meal& meal);
  // Puts the plate or the drink (`body`) at (x, y) on the table, upright at its table height; false (nothing
  // moves) for another body or a spot where it would not stand on the table (Support.h). Takes effect for the
  // current request (a prepare request's drink spot, the plate a meal starts with).
  bool placeOnTable(const std::string& body, double x, double y);
  // The user's answer to "would your view be blocked with the arm at q?" (the web study's question about an
  // egocentric picture of a configuration): viewBlocked(q) or viewClear(q), judged like a move of the arm to q;
  // `score` receives q's occlusion score. The world is left as it was.
  sim::FeedbackEvent viewAnswer(const world::ArmConfig& q, double* score = nullptr);
  // The occlusion score of the user's view with the arm at q (the world is left as it was).
  double occlusionAt(const world::ArmConfig& q);
  const FeedingUser& user() const { return shared().user; }

 private:
  friend class sim::SimulatorBase<FeedingSimulator, const FeedingShared, actions::RobotSimulator>;
  FeedingSimulator(std::shared_ptr<const FeedingShared> shared, const sim::SimulatorOptions& options,
                   sim::WorldRole role, std::uint64_t seed);
  std::optional<sim::StepResult> actOnSimulatorState(const sim::ActionCall& call) override;
  sim::StepResult afterApplied(const sim::ActionCall& call, const actions::RobotActionResult& result,
                               sim::StepResult step) override;
  // The caregiver puts the utensil back, opens the gripper and folds the arm; the request ends unsatisfied.
  sim::StepResult afterFailure(sim::StepResult step) override;
  // afterApplied for waitForUser: the user's answers when a bite is done.
  sim::StepResult waitedForUser(const std::string& signal, sim::StepResult step);
  struct Progress {
    bool biteTaken = false;
    bool drinkOffered = false;
    bool viewBlocked = false;
    int utterancesAtStart = 0;
    std::string dip = "noDip";
    std::string signal;
    double userClearance = kClearanceCap;  // the closest the robot came to the user in this request, metres
    std::string nearest;                   // "robot geom - user geom" of that closest approach
    // The smallest (distance - keep-out distance) of any robot/user geom pair in this request (RobotDistance.h):
    // negative only if the robot entered a keep-out zone the collision checks declare.
    double userKeepOutSlack = kClearanceCap;
  };
  static constexpr double kClearanceCap = 0.5;  // metres; farther is reported as this
  // Lowers progress_.userClearance (and userKeepOutSlack) to the robot's distance to the user (and its slack to the
  // keep-out distances) at each waypoint of an executed path.
  // `call`'s declared exceptions (the bite's `allow`) set what each pair must keep, as they did for its motion.
  void trackClearance(const sim::ActionCall& call, const std::vector<world::ArmConfig>& path);
  void serveMeal();  // draws the next meal: food, the two sauces on the table, the setting, the table
  // Puts the table of `shape` (Meal::table) in place and the other away, then the plate back on it if need be.
  void setTable(const std::string& shape);
  // Puts the friend and the TV the setting names in the scene and parks the others under the floor (fixtures of
  // class visual: they change pictures only, never what the robot may do).
  void showSetting();
  void startRequest(Request r);
  void nextRequest();
  void restoreHome();
  sim::StepResult complete(sim::StepResult r, bool satisfied);
  world::Pose2 randomXY(const TableAreas::Box& box);

  // The scene's fixtures as loaded: the table in use, the other parked; the friend and the TV where they appear.
  std::map<std::string, world::Pose3> tablePoses_;
  std::size_t cycle_ = 0;
  Request request_ = Request::Food;
  std::string food_;
  std::vector<std::string> dips_;
  std::string setting_;
  std::string table_ = "rectangular";
  std::vector<int> userBodies_;  // the user's body and head (robotDistanceTo)
  Progress progress_;
};

}  // namespace cbtl::domains::feeding
