// CookingUser: critiques against the hidden ranges (bounds included), meal verdicts, and the shift rule.
#include "domains/cooking/CookingUser.h"
#include "domains/cooking/CookingWorld.h"

#include <gtest/gtest.h>

namespace {

using namespace cbtl::domains::cooking;

const IngredientTaste& seasoningTaste(const CookingUser& u, Ingredient i) {
  return u.meal("seasoning")->ingredients.at(i);
}

TEST(CookingUser, PaperDefault) {
  const CookingUser u = CookingUser::paperDefault();
  ASSERT_NE(u.meal("seasoning"), nullptr);
  EXPECT_EQ(u.meal("soup"), nullptr);
  EXPECT_EQ(u.requiredIngredients(), (std::vector<Ingredient>{Ingredient::Salt, Ingredient::Pepper}));
  for (Ingredient i : {Ingredient::Salt, Ingredient::Pepper}) {
    EXPECT_EQ(seasoningTaste(u, i).temperature.lo, 2.8);
    EXPECT_EQ(seasoningTaste(u, i).temperature.hi, 3.2);
    EXPECT_EQ(seasoningTaste(u, i).quantity.lo, 0.95);
    EXPECT_EQ(seasoningTaste(u, i).quantity.hi, 1.0);
  }
  EXPECT_EQ(u.quantityMin(Ingredient::Salt), 0.95);
  EXPECT_FALSE(u.quantityMin(Ingredient::Sugar).has_value());
}

TEST(CookingUser, CritiqueBoundsAreInclusiveInTicks) {
  const IngredientTaste taste = seasoningTaste(CookingUser::paperDefault(), Ingredient::Salt);
  EXPECT_EQ(CookingUser::critique(taste, ticksToTemperature(27), 0.97).heat, TempCritique::WantHotter);
  EXPECT_EQ(CookingUser::critique(taste, ticksToTemperature(28), 0.97).heat, TempCritique::Good);
  EXPECT_EQ(CookingUser::critique(taste, ticksToTemperature(32), 0.97).heat, TempCritique::Good);
  EXPECT_EQ(CookingUser::critique(taste, ticksToTemperature(33), 0.97).heat, TempCritique::WantColder);
  EXPECT_EQ(CookingUser::critique(taste, 3.0, 0.94).amount, AmountCritique::WantMore);
  EXPECT_EQ(CookingUser::critique(taste, 3.0, 0.95).amount, AmountCritique::Good);
  EXPECT_EQ(CookingUser::critique(taste, 3.0, 1.0).amount, AmountCritique::Good);
  EXPECT_EQ(CookingUser::critique(taste, 3.0, 1.01).amount, AmountCritique::WantLess);
  EXPECT_TRUE(CookingUser::critique(taste, 3.0, 0.97).good());
}

TEST(CookingUser, CritiqueNamesMatchTheLanguage) {
  EXPECT_EQ(critiqueName(TempCritique::Good), "tempGood");
  EXPECT_EQ(critiqueName(TempCritique::WantHotter), "wantHotter");
  EXPECT_EQ(critiqueName(TempCritique::WantColder), "wantColder");
  EXPECT_EQ(critiqueName(AmountCritique::Good), "amountGood");
  EXPECT_EQ(critiqueName(AmountCritique::WantMore), "wantMore");
  EXPECT_EQ(critiqueName(AmountCritique::WantLess), "wantLess");
}

TEST(CookingUser, Verdicts) {
  const CookingUser u = CookingUser::paperDefault();
  const Tasted salt{Ingredient::Salt, 3.0, 0.97}, pepper{Ingredient::Pepper, 3.0, 0.97};
  EXPECT_TRUE(u.judge("seasoning", {salt, pepper}).satisfied);

  const MealVerdict missing = u.judge("seasoning", {salt});
  EXPECT_FALSE(missing.satisfied);
  ASSERT_EQ(missing.critiques.size(), 1u);
  EXPECT_TRUE(missing.critiques[0].has_value());

  const MealVerdict unknownMeal = u.judge("soup", {salt, pepper});
  EXPECT_FALSE(unknownMeal.satisfied);
  EXPECT_FALSE(unknownMeal.critiques[0].has_value());
  EXPECT_FALSE(unknownMeal.reason.empty());

  const MealVerdict extra = u.judge("seasoning", {salt, pepper, Tasted{Ingredient::Sugar, 3.0, 1.0}});
  EXPECT_FALSE(extra.satisfied);
  EXPECT_FALSE(extra.critiques[2].has_value());

  const MealVerdict hot = u.judge("seasoning", {salt, Tasted{Ingredient::Pepper, 3.3, 0.97}});
  EXPECT_FALSE(hot.satisfied);
  EXPECT_EQ(hot.critiques[1]->heat, TempCritique::WantColder);
}

TEST(CookingUser, RangeScaling) {
  const Range r{2.8, 3.2};
  const Range doubled = r.scaledAboutZero(2.0);
  EXPECT_DOUBLE_EQ(doubled.lo, 5.8);
  EXPECT_DOUBLE_EQ(doubled.hi, 6.2);
  const Range clipped = r.scaledAboutZero(0.0);
  EXPECT_EQ(clipped.lo, 0.0);
  EXPECT_NEAR(clipped.hi, 0.2, 1e-12);  // (3.2 - 2.8) / 2 is not exactly 0.2
}

TEST(CookingUser, ShiftDrawsOneFactorPerIngredientPerAttribute) {
  CookingUser u = CookingUser::paperDefault();
  cbtl::rt::Rng rng(3);
  cbtl::rt::Rng replay(3);
  u.shift(rng, 0.9, 1.1);
  EXPECT_EQ(u.shiftCount(), 1);
  for (Ingredient i : {Ingredient::Salt, Ingredient::Pepper}) {
    const double fT = replay.uniform(0.9, 1.1), fQ = replay.uniform(0.9, 1.1);
    const IngredientTaste& t = seasoningTaste(u, i);
    EXPECT_DOUBLE_EQ(t.temperature.centre(), 3.0 * fT);
    EXPECT_NEAR(t.temperature.halfWidth(), 0.2, 1e-12);
    EXPECT_DOUBLE_EQ(t.quantity.centre(), 0.975 * fQ);
    EXPECT_NEAR(t.quantity.halfWidth(), 0.025, 1e-12);
  }
}

}  // namespace
