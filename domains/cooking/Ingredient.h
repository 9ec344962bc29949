// Ingredient.h — the four ingredients of the Cooking domain and their names in cooking.cbtl.
//
// The names ("salt", "pepper", "sugar", "flour") are the members of the language's `enum Ingredient`; the
// simulator maps values by name, so the order here is only this library's iteration order (it fixes the
// order of RNG draws, hence determinism, but never the meaning of a value).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace cbtl::domains::cooking {

enum class Ingredient { Salt, Pepper, Sugar, Flour };

inline constexpr std::size_t kIngredientCount = 4;
inline constexpr std::array<Ingredient, kIngredientCount> kAllIngredients = {Ingredient::Salt, Ingredient::Pepper,
                                                                             Ingredient::Sugar, Ingredient::Flour};

// Position of `ingredient` in kAllIngredients, for per-ingredient arrays.
constexpr std::size_t indexOf(Ingredient ingredient) { return static_cast<std::size_t>(ingredient); }

// The .cbtl member name, e.g. "salt".
std::string_view ingredientName(Ingredient ingredient);
// The ingredient named `name` (exact, case-sensitive, as in cooking.cbtl); nullopt for any other text.
std::optional<Ingredient> ingredientFromName(std::string_view name);

}  // namespace cbtl::domains::cooking
