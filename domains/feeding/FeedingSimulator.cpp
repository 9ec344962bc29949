#include "domains/feeding/FeedingSimulator.h"

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
// Draws of a spot on the table before a caregiver gives up looking for one where the body stands and is clear.
constexpr int kSpotAttempts = 100;

// The paper's five foods and four sauces (noDip is always possible), and its meal settings (MealSetting).
const std::vector<std::string> kFoods = {"french fries", "raw vegetables", "potato wedges", "carrot sticks",
                                         "tater tots"};
const std::vector<std::string> kDips = {"ketchup", "bbqSauce", "ranch", "hummus"};
const std::vector<std::string> kSettings = {"alone", "withFriend", "withTv", "withFriendAndTv"};

sim::Value foodValue(const std::string& food) { return sim::Value::name(foodEntry(food)); }

sim::StepResult unknownAction(std::string message) {
  sim::StepResult r;
  r.status = sim::ActionStatus::UnknownAction;
  r.message = std::move(message);
  return r;
}

// One answer about a choice: `answer`(leading..., offered, ideal), then `turnedDown`(leading..., choice) for every
// other choice the user neither got nor named (naming the ideal among them turns the rest down).
void answerAmong(std::vector<sim::FeedbackEvent>& out, const std::vector<sim::Value>& leading, const char* answer,
                 const char* turnedDown, const std::vector<std::string>& choices, const std::string& offered,
                 const std::string& ideal) {
  std::vector<sim::Value> args = leading;
  args.push_back(sim::Value::name(offered));
  args.push_back(sim::Value::name(ideal));
  out.push_back({answer, std::move(args)});
  for (const auto& choice : choices) {
    if (choice == offered || choice == ideal) continue;
    std::vector<sim::Value> other = leading;
    other.push_back(sim::Value::name(choice));
    out.push_back({turnedDown, std::move(other)});
  }
}

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

FeedingSimulator::FeedingSimulator(const ProgramFacts& program, const sim::SimulatorOptions&, std::uint64_t seed,
                                   FeedingUser user)
    // Braces: the arguments are evaluated in order, so a program without a scene is told so first.
    : FeedingSimulator{home::programScene(program, "feeding"), std::make_shared<const FeedingUser>(std::move(user)),
                       TableAreas::of(program), seed} {}

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

FeedingSimulator::FeedingSimulator(std::shared_ptr<const world::Scene> scene, std::shared_ptr<const FeedingUser> user,
                                   TableAreas areas, std::uint64_t seed)
    : scene_(std::move(scene)),
      user_(std::move(user)),
      areas_(areas),
      world_(std::make_unique<world::World>(scene_)),
      actions_(FeedingActions::forScene(*scene_)) {
  scenePoses_ = world_->workspace().state().objects;
  tablePoses_ = world_->workspace().state().fixtures;
  for (const char* body : {"user", "user_head"})
    if (const int id = scene_->bodyId(body); id >= 0) userBodies_.push_back(id);
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
  s.objects = scenePoses_;
  const world::Pose2 plate = randomXY(areas_.plate);
  s.objects["plate"].position.x() = plate.x;
  s.objects["plate"].position.y() = plate.y;
  world_->workspace().setState(s);
  world_->utterances().clear();
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
}

void FeedingSimulator::setTable(const std::string& shape) {
  table_ = shape;
  world::Workspace& ws = world_->workspace();
  const auto inUse = tablePoses_.find(kRectangularTable), parked = tablePoses_.find(kRoundTable);
  if (inUse == tablePoses_.end() || parked == tablePoses_.end()) return;  // a scene with one table: recorded only
  const bool round = shape == "circular";
  ws.setFixturePose(kRectangularTable, round ? parked->second : inUse->second);
  ws.setFixturePose(kRoundTable, round ? inUse->second : parked->second);
  // A plate left where the other table reached is put back on this one (the drink is off the table between meals).
  Pose3 plate = *ws.objectPose("plate");
  if (world::supportAt(ws, "plate", plate).supported()) return;
  for (int i = 0; i < kSpotAttempts; ++i) {
    const world::Pose2 xy = randomXY(areas_.plate);
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
  cycle_ = 0;
  startRequest(Request::Food);
}

bool FeedingSimulator::placeOnTable(const std::string& body, double x, double y) {
  if (body != "plate" && body != "drink") return false;
  world::Workspace& ws = world_->workspace();
  Pose3 pose = *ws.objectPose(body);
  pose.position = Eigen::Vector3d(x, y, scenePoses_.at(body).position.z());
  pose.orientation = scenePoses_.at(body).orientation;
  if (!world::supportAt(ws, body, pose).supported()) return false;
  ws.setObjectPose(body, pose);
  return true;
}

double FeedingSimulator::occlusionAt(const world::ArmConfig& q) { return world::builtins::occlusion(*world_, q); }

sim::FeedbackEvent FeedingSimulator::viewAnswer(const world::ArmConfig& q, double* score) {
  const double s = occlusionAt(q);
  if (score != nullptr) *score = s;
  return sim::FeedbackEvent{user_->viewBlocked(s) ? "viewBlocked" : "viewClear",
                            {sim::Value::vec(std::vector<double>(q.begin(), q.end()))}};
}

void FeedingSimulator::startRequest(Request r) {
  request_ = r;
  progress_ = Progress{};
  progress_.utterancesAtStart = static_cast<int>(world_->utterances().size());
  world::Workspace& ws = world_->workspace();
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
    drink.position.z() = scenePoses_.at("drink").position.z();
    drink.orientation = scenePoses_.at("drink").orientation;
    const Pose3 plate = *ws.objectPose("plate");
    for (int i = 0; i < kSpotAttempts; ++i) {
      const world::Pose2 xy = randomXY(areas_.drink);
      drink.position.x() = xy.x;
      drink.position.y() = xy.y;
      if (world_->clearance().objectDistance("drink", drink, "plate", plate) > 0.01 &&
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
  world::WorldState s = world_->workspace().state();
  s.arm = world::configs::kRetract;
  s.gripper = 1.0;
  s.held.reset();
  s.objects["utensil"] = scenePoses_.at("utensil");
  if (s.objects.count("drink") != 0) s.objects["drink"].orientation = scenePoses_.at("drink").orientation;
  world_->workspace().setState(s);
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
  const world::Workspace& ws = world_->workspace();
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

void FeedingSimulator::trackClearance(const std::vector<world::ArmConfig>& path) {
  if (path.empty() || userBodies_.empty()) return;
  world::Workspace& ws = world_->workspace();
  const world::ArmConfig reached = ws.state().arm;
  for (const auto& q : path) {
    ws.setArm(q);
    const world::RobotDistance d = world::robotDistanceTo(ws, userBodies_, kClearanceCap);
    if (d.distance < progress_.userClearance) {
      progress_.userClearance = d.distance;
      progress_.nearest = fmt::format("{} - {}, keep-out {:.3f} m", d.robotGeom, d.bodyGeom, d.keepOut);
    }
    progress_.userKeepOutSlack = std::min(progress_.userKeepOutSlack, d.slack);
  }
  ws.setArm(reached);
}

sim::StepResult FeedingSimulator::fail(sim::StepResult r) {
  r.status = sim::ActionStatus::Ignored;
  r.consumedStep = true;
  r.taskFailed = true;
  restoreHome();
  return complete(std::move(r), false);
}

sim::StepResult FeedingSimulator::complete(sim::StepResult r, bool satisfied) {
  r.taskDone = true;
  r.hasSatisfaction = true;
  r.satisfaction = satisfied ? 1.0 : -1.0;
  nextRequest();
  return r;
}

sim::StepResult FeedingSimulator::act(const sim::ActionCall& call) {
  world::Workspace& ws = world_->workspace();
  if (call.name == "dipInto") {
    // The world does nothing (FeedingActions.h); the sauce must be one of this meal's.
    if (const std::string e = actions::checkArguments(call, {actions::kNameArg}); !e.empty()) {
      return unknownAction(e);
    }
    sim::StepResult step;
    step.consumedStep = true;
    const std::string entry = dipEntryOfSauce(call.args[0].text);
    if (entry.empty() || std::find(dips_.begin(), dips_.end(), entry) == dips_.end()) {
      step.message = fmt::format("dipInto({}): no such sauce on the table", call.args[0].text);
      return fail(std::move(step));
    }
    progress_.dip = entry;
    return step;
  }
  const auto result = actions_.execute(*world_, call);
  if (!result) {
    return unknownAction(fmt::format("Feeding has no action '{}'", call.name));
  }
  sim::StepResult step = result->toStepResult(call.name);
  if (step.status == sim::ActionStatus::UnknownAction) return step;
  if (step.status == sim::ActionStatus::Ignored) return fail(std::move(step));
  trackClearance(result->armPath);

  if (call.name == "waitForReady") {
    progress_.signal = call.args[0].text;
    return step;
  }
  if (call.name == "moveDrink" && request_ == Request::Prepare) return complete(std::move(step), true);
  if (call.name == "moveArm") {
    const world::ArmConfig q = ws.state().arm;
    const double score = world::builtins::occlusion(*world_, q);
    const bool blocked = user_->viewBlocked(score);
    progress_.viewBlocked = progress_.viewBlocked || blocked;
    step.feedback.push_back(sim::FeedbackEvent{blocked ? "viewBlocked" : "viewClear",
                                               {sim::Value::vec(std::vector<double>(q.begin(), q.end()))}});
    return step;
  }
  if (call.name == "waitForUser") {
    const std::string signal = call.args[0].text;
    if (request_ == Request::Food && signal == "biteTaken") progress_.biteTaken = true;
    if (request_ == Request::Drink && signal == "done") progress_.drinkOffered = true;
    if (request_ == Request::Food && signal == "done") {
      if (!progress_.biteTaken) {
        step.message = "the user was never fed";
        return complete(std::move(step), false);
      }
      const std::string idealDip = user_->idealDip(food_, setting_, dips_);
      const std::string idealSignal = user_->idealSignal(setting_);
      const std::string idealVerbosity = user_->idealVerbosity(setting_);
      const int spoke = static_cast<int>(world_->utterances().size()) - progress_.utterancesAtStart;
      const std::string verbosity = FeedingUser::perceivedVerbosity(spoke);
      const std::string signalGiven = progress_.signal.empty() ? "autoContinue" : progress_.signal;
      std::vector<std::string> choices = dips_;
      choices.push_back("noDip");
      answerAmong(step.feedback, {foodValue(food_)}, "dipAnswer", "dipNotWanted", choices, progress_.dip, idealDip);
      answerAmong(step.feedback, {}, "signalAnswer", "signalNotWanted", FeedingUser::readySignals(), signalGiven,
                  idealSignal);
      answerAmong(step.feedback, {}, "verbosityAnswer", "verbosityNotWanted", FeedingUser::verbosities(), verbosity,
                  idealVerbosity);
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

sim::StepResult FeedingSimulator::idle() {
  sim::StepResult r;
  r.consumedStep = true;
  return r;
}

std::unique_ptr<sim::DomainSimulator> FeedingSimulator::makeEvaluationTwin() const {
  return std::unique_ptr<sim::DomainSimulator>(new FeedingSimulator(scene_, user_, areas_, 0));
}

}  // namespace cbtl::domains::feeding
