#include "domains/cooking/Ingredient.h"

namespace cbtl::domains::cooking {

namespace {
constexpr std::array<std::string_view, kIngredientCount> kNames = {"salt", "pepper", "sugar", "flour"};
}  // namespace

std::string_view ingredientName(Ingredient ingredient) { return kNames[indexOf(ingredient)]; }

std::optional<Ingredient> ingredientFromName(std::string_view name) {
  for (Ingredient ingredient : kAllIngredients) {
    if (kNames[indexOf(ingredient)] == name) return ingredient;
  }
  return std::nullopt;
}

}  // namespace cbtl::domains::cooking
