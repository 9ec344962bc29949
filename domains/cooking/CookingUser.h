// CookingUser.h — the hidden preferences of the Cooking user, their critiques of a served meal, and the
// nonstationary shifts of those preferences (paper appendix, "Nonstationary Preferences").
//
// The user knows some meals by name; a meal lists its required ingredients, each with a closed temperature
// range (temperature units: 1.0 = 10 ticks) and a closed quantity range. The paper's user (paperDefault):
// "seasoning" = salt and pepper, each temperature [2.8, 3.2] and quantity [0.95, 1.0].
// The robot never reads these ranges: it learns them from critiques. Tests and the experiment loop may.
//
// Critiques follow the seed: per ingredient, "good" when the value lies in the range (bounds included),
// otherwise the direction the user wants (hotter/colder, more/less). A meal satisfies the user iff its name
// is known, every required ingredient is present, and every critique is good on both axes.
#pragma once

#include "domains/cooking/Ingredient.h"
#include "runtime/core/Rng.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::domains::cooking {

// A closed interval [lo, hi].
struct Range {
  double lo = 0, hi = 0;
  bool contains(double v) const { return v >= lo && v <= hi; }
  double centre() const { return (lo + hi) / 2; }
  double halfWidth() const { return (hi - lo) / 2; }
  // The seed's shift: same half-width, centre scaled by f, lower bound clipped at 0:
  // [max(0, c*f - r), c*f + r].
  Range scaledAboutZero(double f) const;
};

struct IngredientTaste {
  Range temperature;  // temperature units (served ticks / 10)
  Range quantity;
};

struct MealTaste {
  std::string name;                                   // e.g. "seasoning"
  std::map<Ingredient, IngredientTaste> ingredients;  // the required ingredients and how the user likes them
};

// The names match cooking.cbtl's TempCritique and AmountCritique members (see critiqueName below).
enum class TempCritique { Good, WantHotter, WantColder };
enum class AmountCritique { Good, WantMore, WantLess };
std::string_view critiqueName(TempCritique c);    // "tempGood", "wantHotter", "wantColder"
std::string_view critiqueName(AmountCritique c);  // "amountGood", "wantMore", "wantLess"

// One ingredient as the user tastes it.
struct Tasted {
  Ingredient ingredient = Ingredient::Salt;
  double temperature = 0;  // temperature units
  double quantity = 0;
};

struct Critique {
  TempCritique heat = TempCritique::Good;
  AmountCritique amount = AmountCritique::Good;
  bool good() const { return heat == TempCritique::Good && amount == AmountCritique::Good; }
};

struct MealVerdict {
  bool satisfied = false;
  // One entry per tasted ingredient, in the order given; nullopt where the user has no opinion (the meal
  // name is unknown, or the meal does not use that ingredient) — such a meal is never satisfying.
  std::vector<std::optional<Critique>> critiques;
  std::string reason;  // why the user is not satisfied; empty when satisfied
};

class CookingUser {
 public:
  explicit CookingUser(std::vector<MealTaste> meals);
  // The paper's user: seasoning = salt and pepper, temperature [2.8, 3.2], quantity [0.95, 1.0].
  static CookingUser paperDefault();

  const std::vector<MealTaste>& meals() const { return meals_; }
  const MealTaste* meal(std::string_view name) const;  // nullptr for a meal the user does not know
  // Ingredients that some known meal requires, in kAllIngredients order.
  std::vector<Ingredient> requiredIngredients() const;
  // The smallest quantity the user accepts of `ingredient` over the meals that require it (nullopt if none).
  std::optional<double> quantityMin(Ingredient ingredient) const;

  // How the user judges one ingredient cooked to `temperature` in quantity `quantity`.
  static Critique critique(const IngredientTaste& taste, double temperature, double quantity);
  // The user's verdict on a meal served under the name `mealName` with these ingredients.
  MealVerdict judge(std::string_view mealName, const std::vector<Tasted>& tasted) const;

  // Rescales `ingredient`'s temperature range by fTemperature and its quantity range by fQuantity
  // (Range::scaledAboutZero) in every meal that requires it.
  void rescale(Ingredient ingredient, double fTemperature, double fQuantity);
  // One nonstationary shift: for each required ingredient in kAllIngredients order, draws a temperature
  // factor then a quantity factor from U[lo, hi] (rng.uniform(lo, hi), one word each) and rescales. Counts the
  // shift.
  void shift(rt::Rng& rng, double lo, double hi);
  int shiftCount() const { return shiftCount_; }

 private:
  std::vector<MealTaste> meals_;
  int shiftCount_ = 0;
};

}  // namespace cbtl::domains::cooking
