#include "domains/cooking/CookingSimulator.h"

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::domains::cooking {

namespace {

using sim::ActionCall;
using sim::ActionStatus;
using sim::StepResult;
using sim::Value;

constexpr double kStockLo = 10, kStockHi = 20;  // a restock draws U(10, 20) per ingredient ("more than enough")
constexpr double kSpecQuantityMin = 0.9;        // cooking.cbtl's specQtyMin: unsatisfiable stock stays above it

const char* kindName(Value::Kind kind) {
  switch (kind) {
    case Value::Kind::Number:
      return "a number";
    case Value::Kind::Vector:
      return "a vector";
    case Value::Kind::Name:
      return "a name";
    case Value::Kind::Names:
      return "a set of names";
  }
  return "a value";
}

// Checks the argument count and kinds of `call`; the error message, or empty when they fit.
std::string checkArgs(const ActionCall& call, std::initializer_list<Value::Kind> kinds) {
  if (call.args.size() != kinds.size()) {
    return call.name + " takes " + std::to_string(kinds.size()) + " argument(s), got " +
           std::to_string(call.args.size());
  }
  std::size_t i = 0;
  for (Value::Kind kind : kinds) {
    if (call.args[i].kind != kind) {
      return call.name + ": argument " + std::to_string(i + 1) + " must be " + kindName(kind) + ", got " +
             kindName(call.args[i].kind);
    }
    ++i;
  }
  return {};
}

void validate(const sim::SimulatorOptions& o) {
  if (o.shiftEvery < 0) throw std::invalid_argument("cooking: shiftEvery must be >= 0");
  if (!std::isfinite(o.shiftLo) || !std::isfinite(o.shiftHi) || o.shiftLo > o.shiftHi) {
    throw std::invalid_argument("cooking: the shift factor range [shiftLo, shiftHi] must be finite and ordered");
  }
  if (!(o.unsatisfiableStockProbability >= 0 && o.unsatisfiableStockProbability <= 1)) {
    throw std::invalid_argument("cooking: unsatisfiableStockProbability must be in [0, 1]");
  }
}

}  // namespace

std::string potName(std::size_t pot) { return "pot" + std::to_string(pot); }

bool potFromName(std::string_view name, std::optional<std::size_t>& pot) {
  if (name == kNoPotName) {
    pot.reset();
    return true;
  }
  for (std::size_t i = 0; i < kPotCount; ++i) {
    if (name == potName(i)) {
      pot = i;
      return true;
    }
  }
  return false;
}

CookingSimulator::CookingSimulator(const sim::SimulatorOptions& options, std::uint64_t seed)
    : CookingSimulator(options, seed, CookingUser::paperDefault()) {}

CookingSimulator::CookingSimulator(const sim::SimulatorOptions& options, std::uint64_t seed, CookingUser user)
    : CookingSimulator(std::make_shared<CookingUser>(std::move(user)), options, sim::WorldRole::Training, seed) {}

CookingSimulator::CookingSimulator(std::shared_ptr<CookingUser> user, const sim::SimulatorOptions& options,
                                   sim::WorldRole role, std::uint64_t seed)
    : SimulatorBase(std::move(user), options, role), shiftRng_(rt::splitMix64(seed)) {
  validate(options);
  reset(seed);
}

void CookingSimulator::reset(std::uint64_t seed) {
  rng_.seed(seed);
  restock();
}

void CookingSimulator::restock() {
  Stock stock{};
  for (Ingredient ingredient : kAllIngredients) stock[indexOf(ingredient)] = rng_.uniform(kStockLo, kStockHi);
  const double p = options().unsatisfiableStockProbability;
  // No draw at all when the option is off, so the default stream is the same as without the feature.
  if (p > 0 && rng_.uniform() < p) {
    const std::vector<Ingredient> required = user().requiredIngredients();
    if (!required.empty()) {
      const Ingredient scarce = required[rng_.index(required.size())];
      const double userMin = user().quantityMin(scarce).value_or(kSpecQuantityMin);
      double q = kSpecQuantityMin;
      if (userMin > kSpecQuantityMin) {
        q = rng_.uniform(kSpecQuantityMin, userMin);
        if (q >= userMin) q = std::nextafter(userMin, kSpecQuantityMin);  // u < 1, but lo + (hi-lo)*u may round up
      }
      stock[indexOf(scarce)] = q;
    }
  }
  world_.reinitialize(stock);
}

sim::Observation CookingSimulator::observe() const {
  sim::Observation o;
  for (Ingredient ingredient : kAllIngredients) {
    o["stock[" + std::string(ingredientName(ingredient)) + "]"] = Value::num(world_.stock(ingredient));
  }
  return o;
}

StepResult CookingSimulator::act(const ActionCall& call) {
  StepResult result;
  if (call.name == "movePot") {
    result = movePot(call);
  } else if (call.name == "addIngredient") {
    result = addIngredient(call);
  } else if (call.name == "endTick") {
    result = endTick(call);
  } else if (call.name == "serve") {
    result = serve(call);
  } else {
    return sim::unknownActionStep("cooking has no action '" + call.name + "'");
  }
  finishStep(result);
  if (result.taskDone) restock();  // after the shift, so the new kitchen is drawn against the current user
  return result;
}

StepResult CookingSimulator::idle() {
  StepResult result = cookingTick("idle: one cooking tick");
  finishStep(result);
  return result;
}

void CookingSimulator::finishStep(StepResult& result) {
  if (!result.consumedStep) return;
  ++steps_;
  if (shiftsUser() && options().shiftEvery > 0 && steps_ % options().shiftEvery == 0) {
    sharedPointer()->shift(shiftRng_, options().shiftLo, options().shiftHi);
    result.preferencesChanged = options().announceShifts;
  }
}

StepResult CookingSimulator::movePot(const ActionCall& call) {
  if (std::string e = checkArgs(call, {Value::Kind::Name, Value::Kind::Vector}); !e.empty())
    return sim::unknownActionStep(e);
  std::optional<std::size_t> pot;
  if (!potFromName(call.args[0].text, pot))
    return sim::unknownActionStep("movePot: '" + call.args[0].text + "' is not a Pot");
  const std::vector<double>& position = call.args[1].vector;
  if (position.size() != 2) {
    return sim::unknownActionStep("movePot: position must be a vec<2>, got " + std::to_string(position.size()) +
                                  " components");
  }
  StepResult r;
  r.consumedStep = true;
  if (!pot) {
    r.status = ActionStatus::Ignored;
    r.message = "movePot: noPot is not a pot";
    return r;
  }
  switch (world_.movePot(*pot, position[0], position[1])) {
    case MoveOutcome::Moved:
      r.status = ActionStatus::Applied;
      break;
    case MoveOutcome::NoSuchPot:  // potFromName only yields valid indices
    case MoveOutcome::BadPosition:
      r.status = ActionStatus::Ignored;
      r.message = "movePot: " + potName(*pot) + " position is not finite";
      break;
    case MoveOutcome::LeavesStove:
      r.status = ActionStatus::Ignored;
      r.message = "movePot: " + potName(*pot) + " would not lie on the stove";
      break;
    case MoveOutcome::Overlaps:
      r.status = ActionStatus::Ignored;
      r.message = "movePot: " + potName(*pot) + " would overlap another pot";
      break;
  }
  return r;
}

StepResult CookingSimulator::addIngredient(const ActionCall& call) {
  if (std::string e = checkArgs(call, {Value::Kind::Name, Value::Kind::Name, Value::Kind::Number}); !e.empty()) {
    return sim::unknownActionStep(e);
  }
  const std::optional<Ingredient> ingredient = ingredientFromName(call.args[0].text);
  if (!ingredient) return sim::unknownActionStep("addIngredient: '" + call.args[0].text + "' is not an Ingredient");
  std::optional<std::size_t> pot;
  if (!potFromName(call.args[1].text, pot)) {
    return sim::unknownActionStep("addIngredient: '" + call.args[1].text + "' is not a Pot");
  }
  StepResult r;  // no step: the addition waits for the next cooking tick
  if (!pot) {
    r.status = ActionStatus::Ignored;
    r.message = "addIngredient: noPot is not a pot";
    return r;
  }
  const std::string what = std::string(ingredientName(*ingredient)) + " to " + potName(*pot);
  switch (world_.queueAddition(*ingredient, *pot, call.args[2].number)) {
    case AddOutcome::Queued:
      r.status = ActionStatus::Applied;
      break;
    case AddOutcome::NoSuchPot:
    case AddOutcome::BadQuantity:
      r.status = ActionStatus::Ignored;
      r.message = "addIngredient: " + what + ": the quantity must be positive";
      break;
    case AddOutcome::PotNotEmpty:
      r.status = ActionStatus::Ignored;
      r.message = "addIngredient: " + what + ": the pot is not empty";
      break;
    case AddOutcome::NotEnoughStock:
      r.status = ActionStatus::Ignored;
      r.message = "addIngredient: " + what + ": not enough " + std::string(ingredientName(*ingredient)) + " left";
      break;
  }
  return r;
}

StepResult CookingSimulator::endTick(const ActionCall& call) {
  if (std::string e = checkArgs(call, {}); !e.empty()) return sim::unknownActionStep(e);
  return cookingTick({});
}

StepResult CookingSimulator::cookingTick(std::string message) {
  world_.tick();
  StepResult r;
  r.consumedStep = true;
  r.message = std::move(message);
  return r;
}

StepResult CookingSimulator::serve(const ActionCall& call) {
  if (std::string e = checkArgs(call, {Value::Kind::Name}); !e.empty()) return sim::unknownActionStep(e);
  const std::string& mealName = call.args[0].text;
  const std::vector<PotContent> contents = world_.contents();
  std::vector<Tasted> tasted;
  for (const PotContent& c : contents) {
    tasted.push_back(Tasted{c.ingredient, ticksToTemperature(c.temperatureTicks), c.quantity});
  }
  const MealVerdict verdict = user().judge(mealName, tasted);

  StepResult r;
  r.consumedStep = true;
  r.taskDone = true;
  r.hasSatisfaction = true;
  r.satisfaction = verdict.satisfied ? 1.0 : -1.0;
  r.message =
      verdict.satisfied ? "served " + mealName + ": the user enjoyed it" : "served " + mealName + ": " + verdict.reason;
  if (!world_.queuedAdditions().empty()) r.message += " (additions queued after the last tick were dropped)";
  const int total = world_.mealTicks();
  for (std::size_t i = 0; i < contents.size(); ++i) {
    if (!verdict.critiques[i]) continue;
    const Critique& c = *verdict.critiques[i];
    r.feedback.push_back(sim::FeedbackEvent{
        "mealCritique",
        {Value::name(mealName), Value::name(std::string(ingredientName(contents[i].ingredient))),
         Value::num(contents[i].startTick), Value::num(total), Value::num(contents[i].quantity),
         Value::name(std::string(critiqueName(c.heat))), Value::name(std::string(critiqueName(c.amount)))}});
  }
  return r;
}

}  // namespace cbtl::domains::cooking
