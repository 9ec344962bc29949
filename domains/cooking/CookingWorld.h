// CookingWorld.h — the stove, its four pots and the pantry: the physical state of the Cooking domain and
// its deterministic dynamics (no randomness, no user; CookingSimulator draws the stock and owns the user).
//
// Frame and units: the stove is the square [0, 10] x [0, 10] in stove units, origin at one corner, axes
// along its edges; a pot is a disc of fixed radius (pot0..pot3: 0.5, 1.0, 0.5, 0.5) whose centre is given in
// that frame. Quantities are in the units of cooking.cbtl's `stock` (the spec's 0.9 .. 1.1). Temperatures
// are kept as integer *ticks*: one tick is 0.1 temperature units, the heat a pot gains in one cooking tick
// (the reference's float accumulation put values such as 3.2 on either side of a bound).
//
// Time: the cooking clock advances only in tick(): every pot holding an ingredient gains one temperature
// tick if it is on the stove, or loses one (never below 0) if it is off; then the additions queued since
// the previous tick go into their pots. Moving a pot takes a robot step but is not a cooking tick (it does
// not heat), so an ingredient added before tick s of a meal and served after T ticks, in a pot that stayed
// on the stove, is served at exactly T - s - 1 ticks — cooking.cbtl's heatTicks(start, total).
#pragma once

#include "domains/cooking/Ingredient.h"

#include <array>
#include <optional>
#include <vector>

namespace cbtl::domains::cooking {

inline constexpr double kStoveSize = 10.0;   // stove units; the stove is [0, 10] x [0, 10]
inline constexpr std::size_t kPotCount = 4;  // pot0 .. pot3; pots are addressed by index 0 .. 3
inline constexpr std::array<double, kPotCount> kPotRadius = {0.5, 1.0, 0.5, 0.5};  // stove units
inline constexpr int kTicksPerTemperatureUnit = 10;                                // 1 tick = 0.1 temperature units

// The temperature, in temperature units, of `ticks` ticks. Division (not accumulation) is exact to the
// nearest double, so 28 ticks compare equal to the literal 2.8.
inline double ticksToTemperature(int ticks) { return ticks / static_cast<double>(kTicksPerTemperatureUnit); }

using Stock = std::array<double, kIngredientCount>;  // indexed by indexOf(Ingredient)

struct PotState {
  double radius = 0;  // stove units
  bool onStove = false;
  double x = 0, y = 0;                   // centre in the stove frame; meaningful only when onStove
  std::optional<Ingredient> ingredient;  // what the pot holds (at most one ingredient)
  double quantity = 0;                   // of `ingredient`; 0 when empty
  int temperatureTicks = 0;              // 0 when the ingredient went in
  int startTick = 0;                     // the meal tick (ticks before the one that added it) of the addition
};

// An addition waiting for the next tick.
struct Addition {
  Ingredient ingredient = Ingredient::Salt;
  std::size_t pot = 0;
  double quantity = 0;
};

enum class MoveOutcome {
  Moved,
  NoSuchPot,    // pot index >= kPotCount
  BadPosition,  // a coordinate is not finite
  LeavesStove,  // the disc would not lie inside the stove (touching the edge is inside)
  Overlaps,     // the disc would overlap another on-stove pot (centre distance < r1 + r2; touching is fine)
};

enum class AddOutcome {
  Queued,
  NoSuchPot,       // pot index >= kPotCount
  BadQuantity,     // not finite or not positive
  PotNotEmpty,     // the pot holds an ingredient, or an addition to it is already queued for this tick
  NotEnoughStock,  // more than the stock left after the additions already queued for this tick
};

// One ingredient as it leaves the stove.
struct PotContent {
  std::size_t pot = 0;
  Ingredient ingredient = Ingredient::Salt;
  double quantity = 0;
  int startTick = 0;
  int temperatureTicks = 0;
};

class CookingWorld {
 public:
  // All pots off the stove and empty, an empty pantry, meal tick 0.
  CookingWorld();

  // A fresh kitchen for a new meal: pots off the stove, empty and at 0 ticks, the pantry set to `stock`,
  // meal tick 0, no queued additions.
  void reinitialize(const Stock& stock);

  // Puts pot `pot` on the stove with its centre at (x, y), or refuses (the world is then unchanged).
  // A pot already on the stove may be moved; it never collides with itself.
  MoveOutcome movePot(std::size_t pot, double x, double y);
  // Takes pot `pot` off the stove (always allowed, as in the seed); it then cools at every tick. cooking.cbtl
  // has no action for this (its plans never take a pot off), so only tests and other C++ callers use it.
  // Returns false for an index >= kPotCount.
  bool removeFromStove(std::size_t pot);

  // Queues `quantity` of `ingredient` for pot `pot`, to go in at the next tick, or refuses. The checks see the
  // additions already queued, so a queued addition always goes in: the pot is empty, the stock suffices.
  // Allowed whether or not the pot is on the stove (as in the seed); a pot off the stove does not heat.
  AddOutcome queueAddition(Ingredient ingredient, std::size_t pot, double quantity);

  // One cooking tick (see the header comment). Returns the additions that went into their pots.
  std::vector<Addition> tick();

  // What the pots hold, in pot order (empty pots are left out).
  std::vector<PotContent> contents() const;

  const std::array<PotState, kPotCount>& pots() const { return pots_; }
  const PotState& pot(std::size_t index) const { return pots_.at(index); }
  const Stock& stock() const { return stock_; }
  double stock(Ingredient ingredient) const { return stock_[indexOf(ingredient)]; }
  // Ticks of the current meal so far (the `total` of a meal served now).
  int mealTicks() const { return mealTicks_; }
  const std::vector<Addition>& queuedAdditions() const { return queued_; }

 private:
  std::array<PotState, kPotCount> pots_{};
  Stock stock_{};
  int mealTicks_ = 0;
  std::vector<Addition> queued_;
};

}  // namespace cbtl::domains::cooking
