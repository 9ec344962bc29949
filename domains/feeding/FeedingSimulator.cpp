#include "domains/feeding/FeedingSimulator.h"

#include "robot/actions/ClearanceExceptions.h"

#include "domains/feeding/BiteAnswers.h"
#include "domains/feeding/FeedingActions.h"
#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "robot/actions/CallArguments.h"
#include "robot/world/RobotDistance.h"
#include "robot/world/Support.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace cbtl::domains::feeding {

namespace {

using world::Pose3;

// Where the drink waits while it is not in use: off the table, out of every check of the table.
constexpr double kDrinkParkedX = 0.55, kDrinkParkedY = 1.60;
// The table fixtures of feeding.xml by shape (Meal::table); the scene's starting pose of "table" is where the table
// in use stands, that of "table_round" where the other one is parked.
constexpr const char* kRectangularTable = "table";
constexpr const char* kRoundTable = "table_round";
// The fixtures of a meal's setting (MealSetting), and how far below its place an absent one is parked.
constexpr const char* kFriend = "friend";
constexpr const char* kTv = "tv";
constexpr double kParkedDepth = 3.0;
// Draws of a spot on the table before a caregiver gives up looking for one where the body stands and is clear.
constexpr int kSpotAttempts = 100;

// The paper's five foods and four sauces (noDip is always possible), and its meal settings (MealSetting).
const std::vector<std::string> kFoods = {"french fries", "raw vegetables", "potato wedges", "carrot sticks",
                                         "tater tots"};
const std::vector<std::string> kDips = {"ketchup", "bbqSauce", "ranch", "hummus"};
const std::vector<std::string> kSettings = {"alone", "withFriend", "withTv", "withFriendAndTv"};

sim::Value foodValue(const std::string& food) { return sim::Value::name(foodEntry(food)); }

}  // namespace

const std::vector<Meal>& paperMeals() {
  static const std::vector<Meal> meals = {
      {"french fries", {"bbqSauce", "ketchup"}, "alone", "rectangular"},
      {"raw vegetables", {"hummus", "ranch"}, "withFriend", "circular"},
      {"potato wedges", {"bbqSauce", "ketchup"}, "withTv", "circular"},
      {"carrot sticks", {"hummus", "ranch"}, "alone", "circular"},
      {"tater tots", {"bbqSauce", "ketchup"}, "withFriendAndTv", "rectangular"},
  };
  return meals;
}

const char* toString(Request r) {
  switch (r) {
    case Request::Food:
      return "food";
    case Request::Prepare:
      return "prepare";
    case Request::Drink:
      return "drink";
  }
  return "?";
}

FeedingSimulator::FeedingSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options,
                                   std::uint64_t seed)
    : FeedingSimulator(program, options, seed,
                       options.participant >= 0
                           ? FeedingUser::participant(static_cast<std::uint64_t>(options.participant))
                           : FeedingUser::paperDefault()) {}

FeedingSimulator::FeedingSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options,
                                   std::uint64_t seed, FeedingUser user)
    // FeedingShared's braces evaluate in order, so a program without a scene is told so before its constants are read.
    : FeedingSimulator{std::make_shared<const FeedingShared>(FeedingShared{home::programScene(program, "feeding"),
                                                                           std::move(user), TableAreas::of(program)}),
                       options, sim::WorldRole::Training, seed} {}

TableAreas TableAreas::of(const ProgramFacts& program) {
  static constexpr const char* kNames[2][4] = {{"plateX0", "plateX1", "plateY0", "plateY1"},
                                               {"drinkX0", "drinkX1", "drinkY0", "drinkY1"}};
  TableAreas areas;
  Box* boxes[2] = {&areas.plate, &areas.drink};
  for (int b = 0; b < 2; ++b) {
    const ProgramFacts::Number* n[4];
    for (int k = 0; k < 4; ++k) n[k] = &requireNumber(program, kNames[b][k], "Feeding's plate and drink areas");
    *boxes[b] = Box{n[0]->value, n[1]->value, n[2]->value, n[3]->value};
    const Box& box = *boxes[b];
    const bool ordered = box.x0 <= box.x1 && box.y0 <= box.y1;  // false for NaN too
    if (!ordered || !std::isfinite(box.x0) || !std::isfinite(box.x1) || !std::isfinite(box.y0) ||
        !std::isfinite(box.y1))
      throw rt::RuntimeError(
          whereOf(n[0]->span),
          fmt::format("the {} area [{} .. {}, {} .. {}] ({} .. {}) is empty or not finite", b == 0 ? "plate" : "drink",
                      box.x0, box.x1, box.y0, box.y1, kNames[b][0], kNames[b][3]));
  }
  return areas;
}

FeedingSimulator::FeedingSimulator(std::shared_ptr<const FeedingShared> shared, const sim::SimulatorOptions& options,
                                   sim::WorldRole role, std::uint64_t seed)
    : SimulatorBase(shared, options, role,
                    actions::RobotSimulator::Setup{
                        "feeding", shared->scene, actions::RobotActions(FeedingActions::forScene(*shared->scene)), 0}) {
  tablePoses_ = world().workspace().state().fixtures;
  for (const char* body : {"user", "user_head"})
    if (const int id = scene().bodyId(body); id >= 0) userBodies_.push_back(id);
  reset(seed);
}

world::Pose2 FeedingSimulator::randomXY(const TableAreas::Box& box) {
  const double x = rng_.uniform(box.x0, box.x1);
  return world::Pose2{x, rng_.uniform(box.y0, box.y1), 0.0};
}

void FeedingSimulator::reset(std::uint64_t seed) {
  rng_.seed(seed);
  world::WorldState s;
  s.arm = world::configs::kRetract;
  s.gripper = 1.0;
  s.objects = scenePoses();
  const world::Pose2 plate = randomXY(shared().areas.plate);
  s.objects["plate"].position.x() = plate.x;
  s.objects["plate"].position.y() = plate.y;
  startEpisode(s);
  cycle_ = rng_.index(4);
  serveMeal();
  startRequest(cycle_ == 2 ? Request::Prepare : cycle_ == 3 ? Request::Drink : Request::Food);
}

void FeedingSimulator::serveMeal() {
  food_ = kFoods[rng_.index(kFoods.size())];
  std::vector<std::string> dips = kDips;
  const std::size_t first = rng_.index(dips.size());
  std::swap(dips[0], dips[first]);
  const std::size_t second = 1 + rng_.index(dips.size() - 1);
  std::swap(dips[1], dips[second]);
  dips_ = {dips[0], dips[1]};
  std::sort(dips_.begin(), dips_.end());
  setting_ = kSettings[rng_.index(kSettings.size())];
  setTable(rng_.index(2) == 0 ? "rectangular" : "circular");
  showSetting();
}

void FeedingSimulator::showSetting() {
  world::Workspace& ws = world().workspace();
  const bool friendThere = setting_ == "withFriend" || setting_ == "withFriendAndTv";
  const bool tvOn = setting_ == "withTv" || setting_ == "withFriendAndTv";
  for (const auto& [name, present] : {std::pair{kFriend, friendThere}, std::pair{kTv, tvOn}}) {
    const auto placed = tablePoses_.find(name);
    if (placed == tablePoses_.end()) continue;  // a scene without it
    world::Pose3 pose = placed->second;
    if (!present) pose.position.z() -= kParkedDepth;
    ws.setFixturePose(name, pose);
  }
}

void FeedingSimulator::setTable(const std::string& shape) {
  table_ = shape;
  world::Workspace& ws = world().workspace();
  const auto inUse = tablePoses_.find(kRectangularTable), parked = tablePoses_.find(kRoundTable);
  if (inUse == tablePoses_.end() || parked == tablePoses_.end()) return;  // a scene with one table: recorded only
  const bool round = shape == "circular";
  ws.setFixturePose(kRectangularTable, round ? parked->second : inUse->second);
  ws.setFixturePose(kRoundTable, round ? inUse->second : parked->second);
  // A plate left where the other table reached is put back on this one (the drink is off the table between meals).
  Pose3 plate = *ws.objectPose("plate");
  if (world::supportAt(ws, "plate", plate).supported()) return;
  for (int i = 0; i < kSpotAttempts; ++i) {
    const world::Pose2 xy = randomXY(shared().areas.plate);
    plate.position.x() = xy.x;
    plate.position.y() = xy.y;
    if (world::supportAt(ws, "plate", plate).supported()) break;
  }
  ws.setObjectPose("plate", plate);
}

void FeedingSimulator::serveMealNow(const Meal& meal) {
  food_ = meal.food;
  dips_ = meal.dips;
  std::sort(dips_.begin(), dips_.end());
  setting_ = meal.setting;
  setTable(meal.table);
  showSetting();
  cycle_ = 0;
  startRequest(Request::Food);
}

bool FeedingSimulator::placeOnTable(const std::string& body, double x, double y) {
  if (body != "plate" && body != "drink") return false;
  world::Workspace& ws = world().workspace();
  Pose3 pose = *ws.objectPose(body);
  pose.position = Eigen::Vector3d(x, y, scenePoses().at(body).position.z());
  pose.orientation = scenePoses().at(body).orientation;
  if (!world::supportAt(ws, body, pose).supported()) return false;
  ws.setObjectPose(body, pose);
  return true;
}

double FeedingSimulator::occlusionAt(const world::ArmConfig& q) { return world::builtins::occlusion(world(), q); }

sim::FeedbackEvent FeedingSimulator::viewAnswer(const world::ArmConfig& q, double* score) {
  const double s = occlusionAt(q);
  if (score != nullptr) *score = s;
  return viewAnswerEvent(q, user().viewBlocked(s));
}

void FeedingSimulator::startRequest(Request r) {
  request_ = r;
  progress_ = Progress{};
  progress_.utterancesAtStart = static_cast<int>(world().utterances().size());
  world::Workspace& ws = world().workspace();
  if (r == Request::Food) {
    Pose3 drink = *ws.objectPose("drink");
    drink.position.x() = kDrinkParkedX;
    drink.position.y() = kDrinkParkedY;
    ws.setObjectPose("drink", drink);
  } else if (r == Request::Prepare) {
    // The drink arrives at a random spot on the table clear of the plate (the caregiver puts it there, standing
    // upright at the table's height: a drink the user held comes back in whatever pose the hand-over left it,
    // and tilted into the table top it could not be moved again).
    Pose3 drink = *ws.objectPose("drink");
    drink.position.z() = scenePoses().at("drink").position.z();
    drink.orientation = scenePoses().at("drink").orientation;
    const Pose3 plate = *ws.objectPose("plate");
    for (int i = 0; i < kSpotAttempts; ++i) {
      const world::Pose2 xy = randomXY(shared().areas.drink);
      drink.position.x() = xy.x;
      drink.position.y() = xy.y;
      if (world().clearance().objectDistance("drink", drink, "plate", plate) > 0.01 &&
          world::supportAt(ws, "drink", drink).supported())
        break;
    }
    ws.setObjectPose("drink", drink);
  }
}

void FeedingSimulator::nextRequest() {
  cycle_ = (cycle_ + 1) % 4;
  if (cycle_ == 0) serveMeal();  // the drink is back with the user: the next meal
  startRequest(cycle_ == 2 ? Request::Prepare : cycle_ == 3 ? Request::Drink : Request::Food);
}

void FeedingSimulator::restoreHome() {
  world::WorldState s = world().workspace().state();
  s.arm = world::configs::kRetract;
  s.gripper = 1.0;
  s.held.reset();
  s.objects["utensil"] = scenePoses().at("utensil");
  if (s.objects.count("drink") != 0) s.objects["drink"].orientation = scenePoses().at("drink").orientation;
  world().workspace().setState(s);
}

std::string FeedingSimulator::requestedTask() const {
  switch (request_) {
    case Request::Food:
      return "feedBite";
    case Request::Prepare:
      return "prepareDrink";
    case Request::Drink:
      return "giveDrink";
  }
  return {};
}

std::vector<std::string> FeedingSimulator::judgedPreferences() const {
  return {"bite", "view", "dip", "signal", "verbosity"};
}

sim::Observation FeedingSimulator::observe() const {
  const world::Workspace& ws = world().workspace();
  const Pose3 plate = *ws.objectPose("plate");
  const Pose3 drink = *ws.objectPose("drink");
  sim::Observation o;
  o["plateXY"] = sim::Value::vec({plate.position.x(), plate.position.y()});
  o["drinkXY"] = sim::Value::vec({drink.position.x(), drink.position.y()});
  o["dipsOnTable"] = sim::Value::names(dips_);
  std::vector<std::string> choices = dips_;
  choices.push_back("noDip");
  o["dipChoices"] = sim::Value::names(choices);
  o["foodOnPlate"] = foodValue(food_);
  o["mealSetting"] = sim::Value::name(setting_);
  return o;
}

void FeedingSimulator::trackClearance(const sim::ActionCall& call, const std::vector<world::ArmConfig>& path) {
  if (path.empty() || userBodies_.empty()) return;
  world::Workspace& ws = world().workspace();
  world::CollisionOptions declared;
  std::string error;  // the executor refused the call already when its exceptions do not resolve
  if (!actions::resolveClearanceExceptions(ws.scene(), call.exceptions, declared.allowances, error)) return;
  const world::ArmConfig reached = ws.state().arm;
  for (const auto& q : path) {
    ws.setArm(q);
    const world::RobotDistance d = world::robotDistanceTo(ws, userBodies_, kClearanceCap, declared);
    if (d.distance < progress_.userClearance) {
      progress_.userClearance = d.distance;
      progress_.nearest = fmt::format("{} - {}, keep-out {:.3f} m", d.robotGeom, d.bodyGeom, d.keepOut);
    }
    progress_.userKeepOutSlack = std::min(progress_.userKeepOutSlack, d.slack);
  }
  ws.setArm(reached);
}

sim::StepResult FeedingSimulator::afterFailure(sim::StepResult step) {
  step.consumedStep = true;
  restoreHome();
  return complete(std::move(step), false);
}

sim::StepResult FeedingSimulator::complete(sim::StepResult r, bool satisfied) {
  r.taskDone = true;
  r.hasSatisfaction = true;
  r.satisfaction = satisfied ? 1.0 : -1.0;
  nextRequest();
  return r;
}

std::optional<sim::StepResult> FeedingSimulator::actOnSimulatorState(const sim::ActionCall& call) {
  if (call.name != "dipInto") return std::nullopt;
  // The world does nothing (FeedingActions.h); the sauce must be one of this meal's.
  if (const std::string e = actions::checkArguments(call, {actions::kNameArg}); !e.empty()) {
    return sim::unknownActionStep(e);
  }
  sim::StepResult step;
  step.consumedStep = true;
  const std::string entry = dipEntryOfSauce(call.args[0].text);
  if (entry.empty() || std::find(dips_.begin(), dips_.end(), entry) == dips_.end()) {
    step.message = fmt::format("dipInto({}): no such sauce on the table", call.args[0].text);
    return failTask(std::move(step));
  }
  progress_.dip = entry;
  return step;
}

sim::StepResult FeedingSimulator::afterApplied(const sim::ActionCall& call, const actions::RobotActionResult& result,
                                               sim::StepResult step) {
  world::Workspace& ws = world().workspace();
  trackClearance(call, result.armPath);
  if (call.name == "waitForReady") {
    progress_.signal = call.args[0].text;
    return step;
  }
  if (call.name == "moveDrink" && request_ == Request::Prepare) return complete(std::move(step), true);
  if (call.name == "moveArm") {
    const world::ArmConfig q = ws.state().arm;
    const double score = world::builtins::occlusion(world(), q);
    const bool blocked = user().viewBlocked(score);
    progress_.viewBlocked = progress_.viewBlocked || blocked;
    step.feedback.push_back(sim::FeedbackEvent{blocked ? "viewBlocked" : "viewClear",
                                               {sim::Value::vec(std::vector<double>(q.begin(), q.end()))}});
    return step;
  }
  if (call.name == "waitForUser") return waitedForUser(call.args[0].text, std::move(step));
  if (call.name == "moveArmToNamed" && request_ == Request::Drink && progress_.drinkOffered && ws.heldObject() < 0) {
    Pose3 drink = *ws.objectPose("drink");
    drink.position.x() = kDrinkParkedX;  // the user keeps the drink by them; the table is clear again
    drink.position.y() = kDrinkParkedY;
    ws.setObjectPose("drink", drink);
    step.preferences = {{"view", !progress_.viewBlocked}};
    step.measures = {{"userClearance", progress_.userClearance}, {"userKeepOutSlack", progress_.userKeepOutSlack}};
    return complete(std::move(step), !progress_.viewBlocked);
  }
  return step;
}

sim::StepResult FeedingSimulator::waitedForUser(const std::string& signal, sim::StepResult step) {
  if (request_ == Request::Food && signal == "biteTaken") progress_.biteTaken = true;
  if (request_ == Request::Drink && signal == "done") progress_.drinkOffered = true;
  if (request_ == Request::Food && signal == "done") {
    if (!progress_.biteTaken) {
      step.message = "the user was never fed";
      return complete(std::move(step), false);
    }
    const std::string idealDip = user().idealDip(food_, setting_, dips_);
    const std::string idealSignal = user().idealSignal(setting_);
    const std::string idealVerbosity = user().idealVerbosity(setting_);
    const int spoke = static_cast<int>(world().utterances().size()) - progress_.utterancesAtStart;
    const std::string verbosity = FeedingUser::perceivedVerbosity(spoke);
    const std::string signalGiven = progress_.signal.empty() ? "autoContinue" : progress_.signal;
    for (auto& event : biteAnswerEvents(BiteOffer{food_, dips_, progress_.dip, signalGiven, verbosity},
                                        BiteIdeals{idealDip, idealSignal, idealVerbosity}))
      step.feedback.push_back(std::move(event));
    step.preferences = {{"view", !progress_.viewBlocked},
                        {"dip", progress_.dip == idealDip},
                        {"signal", signalGiven == idealSignal},
                        {"verbosity", verbosity == idealVerbosity}};
    const bool satisfied =
        std::all_of(step.preferences.begin(), step.preferences.end(), [](const auto& p) { return p.second; });
    step.preferences.insert(step.preferences.begin(), {"bite", satisfied});
    step.measures = {{"userClearance", progress_.userClearance}, {"userKeepOutSlack", progress_.userKeepOutSlack}};
    if (!progress_.nearest.empty())
      step.message = fmt::format("closest to the user: {:.3f} m ({})", progress_.userClearance, progress_.nearest);
    return complete(std::move(step), satisfied);
  }
  return step;
}

}  // namespace cbtl::domains::feeding
