#include "domains/cooking/CookingUser.h"

#include <algorithm>
#include <utility>

namespace cbtl::domains::cooking {

Range Range::scaledAboutZero(double f) const {
  const double c = centre() * f, r = halfWidth();
  return Range{std::max(0.0, c - r), c + r};
}

std::string_view critiqueName(TempCritique c) {
  switch (c) {
    case TempCritique::Good:
      return "tempGood";
    case TempCritique::WantHotter:
      return "wantHotter";
    case TempCritique::WantColder:
      return "wantColder";
  }
  return "tempGood";
}

std::string_view critiqueName(AmountCritique c) {
  switch (c) {
    case AmountCritique::Good:
      return "amountGood";
    case AmountCritique::WantMore:
      return "wantMore";
    case AmountCritique::WantLess:
      return "wantLess";
  }
  return "amountGood";
}

CookingUser::CookingUser(std::vector<MealTaste> meals) : meals_(std::move(meals)) {}

CookingUser CookingUser::paperDefault() {
  const IngredientTaste taste{Range{2.8, 3.2}, Range{0.95, 1.0}};
  return CookingUser({MealTaste{"seasoning", {{Ingredient::Salt, taste}, {Ingredient::Pepper, taste}}}});
}

const MealTaste* CookingUser::meal(std::string_view name) const {
  for (const MealTaste& m : meals_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::vector<Ingredient> CookingUser::requiredIngredients() const {
  std::vector<Ingredient> out;
  for (Ingredient ingredient : kAllIngredients) {
    const bool required = std::any_of(meals_.begin(), meals_.end(),
                                      [&](const MealTaste& m) { return m.ingredients.count(ingredient) > 0; });
    if (required) out.push_back(ingredient);
  }
  return out;
}

std::optional<double> CookingUser::quantityMin(Ingredient ingredient) const {
  std::optional<double> lo;
  for (const MealTaste& m : meals_) {
    auto it = m.ingredients.find(ingredient);
    if (it != m.ingredients.end()) lo = lo ? std::min(*lo, it->second.quantity.lo) : it->second.quantity.lo;
  }
  return lo;
}

Critique CookingUser::critique(const IngredientTaste& taste, double temperature, double quantity) {
  Critique c;
  if (temperature < taste.temperature.lo)
    c.heat = TempCritique::WantHotter;
  else if (temperature > taste.temperature.hi)
    c.heat = TempCritique::WantColder;
  if (quantity < taste.quantity.lo)
    c.amount = AmountCritique::WantMore;
  else if (quantity > taste.quantity.hi)
    c.amount = AmountCritique::WantLess;
  return c;
}

MealVerdict CookingUser::judge(std::string_view mealName, const std::vector<Tasted>& tasted) const {
  MealVerdict verdict;
  verdict.critiques.resize(tasted.size());
  const MealTaste* m = meal(mealName);
  if (!m) {
    verdict.reason = "the user does not know a meal called '" + std::string(mealName) + "'";
    return verdict;
  }
  bool allGood = true;
  std::string unwanted;
  for (std::size_t i = 0; i < tasted.size(); ++i) {
    auto it = m->ingredients.find(tasted[i].ingredient);
    if (it == m->ingredients.end()) {
      if (unwanted.empty()) unwanted = std::string(ingredientName(tasted[i].ingredient));
      continue;
    }
    verdict.critiques[i] = critique(it->second, tasted[i].temperature, tasted[i].quantity);
    allGood = allGood && verdict.critiques[i]->good();
  }
  for (const auto& [ingredient, taste] : m->ingredients) {
    const bool present =
        std::any_of(tasted.begin(), tasted.end(), [&](const Tasted& t) { return t.ingredient == ingredient; });
    if (!present) {
      verdict.reason = m->name + " needs " + std::string(ingredientName(ingredient));
      return verdict;
    }
  }
  if (!unwanted.empty()) {
    verdict.reason = m->name + " has no " + unwanted;
    return verdict;
  }
  if (!allGood) {
    verdict.reason = "not every ingredient was cooked to the user's taste";
    return verdict;
  }
  verdict.satisfied = true;
  return verdict;
}

void CookingUser::rescale(Ingredient ingredient, double fTemperature, double fQuantity) {
  for (MealTaste& m : meals_) {
    auto it = m.ingredients.find(ingredient);
    if (it == m.ingredients.end()) continue;
    it->second.temperature = it->second.temperature.scaledAboutZero(fTemperature);
    it->second.quantity = it->second.quantity.scaledAboutZero(fQuantity);
  }
}

void CookingUser::shift(rt::Rng& rng, double lo, double hi) {
  for (Ingredient ingredient : requiredIngredients()) {
    const double fTemperature = rng.uniform(lo, hi);
    const double fQuantity = rng.uniform(lo, hi);
    rescale(ingredient, fTemperature, fQuantity);
  }
  ++shiftCount_;
}

}  // namespace cbtl::domains::cooking
