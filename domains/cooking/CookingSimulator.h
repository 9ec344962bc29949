// CookingSimulator.h — the Cooking domain behind the runtime's DomainSimulator contract: CookingWorld (stove,
// pots, pantry) plus CookingUser (hidden preferences), speaking exactly the names of domains/cooking/cooking.cbtl.
//
// Actions (values by name; argument kinds as in DomainSimulator.h):
//   movePot(p: Pot, position: vec<2>)     one step; Ignored when the disc leaves the stove, overlaps an on-stove
//                                         pot, or p is noPot. Not a cooking tick (no heating).
//   addIngredient(ing, p: Pot, qty: real) no step; queued for the next cooking tick. Ignored for noPot, a pot that
//                                         is (or is about to be) full, qty above the stock left, or qty <= 0.
//   endTick()                             one step and one cooking tick (CookingWorld::tick).
//   serve(mealName: text)                 one step, no heating. The user judges every filled pot: one
//                                         mealCritique(meal, ing, start, total, qty, heat, amount) event per
//                                         ingredient the user has an opinion on; satisfaction +1 or -1;
//                                         taskDone. Queued additions are dropped. The kitchen is then restocked
//                                         (pots off and empty, stock U(10, 20) each, meal tick 0).
//   idle()                                one step and one cooking tick: the robot did nothing, but time passed;
//                                         additions queued in this tick go in as at endTick.
// An unknown action name, a wrong argument count or kind, or an unknown enum member gives UnknownAction (no
// step, world unchanged) with a message. Observation: "stock[salt]", "stock[pepper]", "stock[sugar]",
// "stock[flour]" (numbers).
//
// Determinism: reset(seed) reseeds the world's rt::Rng (runtime/core/Rng.h) and draws a fresh kitchen. Draw
// order of a restock: stock of salt, pepper, sugar, flour (uniform(lo, hi) each); then, only when
// unsatisfiableStockProbability > 0, one coin (uniform() < p), and if it comes up, one index (index(n)) and one
// quantity (uniform(lo, hi)).
//
// Lifetime state (not touched by reset): the user and the count of consumed steps. A constructed simulator is a
// *training world*: when shiftEvery > 0 it shifts the user (CookingUser::shift with U[shiftLo, shiftHi]) at the
// end of every shiftEvery-th consumed step, drawing from its own shift RNG seeded from the construction seed
// (rt::splitMix64 of it), so the k-th shift is the same whatever the robot did. The step whose end shifts the
// user reports preferencesChanged when announceShifts. A meal served on that step is judged before the shift;
// the kitchen restocked after it sees the shifted user.
//
// Unsatisfiable stock (paper Table 1): after every restock, with probability p one ingredient the user requires
// (uniform over CookingUser::requiredIngredients) gets stock U(0.9, m), m = the user's current minimum quantity
// of it: enough for the public spec (0.9 .. 1.1), too little for the user. If m <= 0.9 no such stock exists;
// the stock is then set to exactly 0.9 (the least the spec allows), which may leave the user satisfiable.
#pragma once

#include "domains/cooking/CookingUser.h"
#include "domains/cooking/CookingWorld.h"
#include "runtime/core/Rng.h"
#include "runtime/sim/SimulatorBase.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace cbtl::domains::cooking {

// The .cbtl members of `enum Pot`: "noPot" (no pot) and "pot0" .. "pot3" (pot indices 0 .. 3).
inline constexpr std::string_view kNoPotName = "noPot";
std::string potName(std::size_t pot);  // "pot0" .. "pot3"
// Parses a Pot member: pot index for "pot0".."pot3", nullopt for "noPot"; false when the name is not a member.
bool potFromName(std::string_view name, std::optional<std::size_t>& pot);

// The evaluation twin is sim::SimulatorBase's: it shares the (mutable) user, which only the training world shifts.
class CookingSimulator final : public sim::SimulatorBase<CookingSimulator, CookingUser> {
 public:
  // A training world with the paper's user (CookingUser::paperDefault). Throws std::invalid_argument for
  // options out of range (shiftEvery < 0, shiftLo > shiftHi, a non-finite bound, p outside [0, 1]).
  CookingSimulator(const sim::SimulatorOptions& options, std::uint64_t seed);
  // A training world with a given user.
  CookingSimulator(const sim::SimulatorOptions& options, std::uint64_t seed, CookingUser user);

  void reset(std::uint64_t seed) override;
  sim::Observation observe() const override;
  sim::StepResult act(const sim::ActionCall& call) override;
  sim::StepResult idle() override;
  // makeEvaluationTwin(): shares the user; its own world and RNG, reset with seed 0 until the caller resets it.
  // Never shifts the user.

  const CookingWorld& world() const { return world_; }
  const CookingUser& user() const { return shared(); }
  // Steps this simulator consumed since construction (reset does not clear it).
  std::int64_t stepCount() const { return steps_; }
  // True for a training world, false for an evaluation twin.
  bool shiftsUser() const { return role() == sim::WorldRole::Training; }

 private:
  friend class sim::SimulatorBase<CookingSimulator, CookingUser>;
  CookingSimulator(std::shared_ptr<CookingUser> user, const sim::SimulatorOptions& options, sim::WorldRole role,
                   std::uint64_t seed);

  sim::StepResult movePot(const sim::ActionCall& call);
  sim::StepResult addIngredient(const sim::ActionCall& call);
  sim::StepResult endTick(const sim::ActionCall& call);
  sim::StepResult serve(const sim::ActionCall& call);
  sim::StepResult cookingTick(std::string message);
  // Counts a consumed step and shifts the user when it is due.
  void finishStep(sim::StepResult& result);
  void restock();

  // rng_ (SimulatorBase): the world's stock and unsatisfiable picks; reseeded by reset.
  rt::Rng shiftRng_;  // the user's shifts; seeded once at construction
  CookingWorld world_;
  std::int64_t steps_ = 0;
};

}  // namespace cbtl::domains::cooking
