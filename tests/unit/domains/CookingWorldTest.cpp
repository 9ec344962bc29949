// CookingWorld: the stove's placement rules, the addition rules and the per-tick heating/cooling, in integer
// temperature ticks.
#include "domains/cooking/CookingWorld.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace cbtl::domains::cooking;

Stock plentiful() { return Stock{15.0, 15.0, 15.0, 15.0}; }

TEST(CookingWorld, StartsEmptyAndOffStove) {
  CookingWorld w;
  w.reinitialize(plentiful());
  for (std::size_t i = 0; i < kPotCount; ++i) {
    EXPECT_FALSE(w.pot(i).onStove);
    EXPECT_FALSE(w.pot(i).ingredient.has_value());
    EXPECT_EQ(w.pot(i).temperatureTicks, 0);
    EXPECT_EQ(w.pot(i).radius, kPotRadius[i]);
  }
  EXPECT_EQ(w.pot(1).radius, 1.0);
  EXPECT_EQ(w.mealTicks(), 0);
  EXPECT_EQ(w.stock(Ingredient::Pepper), 15.0);
}

TEST(CookingWorld, MoveInsideStoveIsApplied) {
  CookingWorld w;
  EXPECT_EQ(w.movePot(0, 2.0, 3.0), MoveOutcome::Moved);
  EXPECT_TRUE(w.pot(0).onStove);
  EXPECT_EQ(w.pot(0).x, 2.0);
  EXPECT_EQ(w.pot(0).y, 3.0);
  // Touching the edge is inside (pot1 has radius 1).
  EXPECT_EQ(w.movePot(1, 1.0, 9.0), MoveOutcome::Moved);
  // A pot may move again; it never collides with itself.
  EXPECT_EQ(w.movePot(0, 2.2, 3.0), MoveOutcome::Moved);
  EXPECT_EQ(w.pot(0).x, 2.2);
}

TEST(CookingWorld, MoveLeavingStoveIsRefused) {
  CookingWorld w;
  EXPECT_EQ(w.movePot(0, 0.4, 5.0), MoveOutcome::LeavesStove);  // radius 0.5 crosses x = 0
  EXPECT_EQ(w.movePot(1, 5.0, 9.5), MoveOutcome::LeavesStove);  // radius 1.0 crosses y = 10
  EXPECT_EQ(w.movePot(2, 11.0, 5.0), MoveOutcome::LeavesStove);
  EXPECT_EQ(w.movePot(3, -3.0, -3.0), MoveOutcome::LeavesStove);
  EXPECT_EQ(w.movePot(3, NAN, 5.0), MoveOutcome::BadPosition);
  EXPECT_EQ(w.movePot(4, 5.0, 5.0), MoveOutcome::NoSuchPot);
  for (const PotState& p : w.pots()) EXPECT_FALSE(p.onStove);
}

TEST(CookingWorld, OverlappingMoveIsRefusedTouchingIsFine) {
  CookingWorld w;
  ASSERT_EQ(w.movePot(1, 5.0, 5.0), MoveOutcome::Moved);     // r = 1.0
  EXPECT_EQ(w.movePot(0, 6.4, 5.0), MoveOutcome::Overlaps);  // r = 0.5, distance 1.4 < 1.5
  EXPECT_FALSE(w.pot(0).onStove);
  EXPECT_EQ(w.movePot(0, 6.5, 5.0), MoveOutcome::Moved);     // distance 1.5 == 1.5: touching
  EXPECT_EQ(w.movePot(2, 6.5, 5.5), MoveOutcome::Overlaps);  // overlaps pot0
  // Off-stove pots do not block.
  ASSERT_TRUE(w.removeFromStove(0));
  EXPECT_EQ(w.movePot(2, 6.5, 5.5), MoveOutcome::Moved);
}

TEST(CookingWorld, AdditionWaitsForTheNextTick) {
  CookingWorld w;
  w.reinitialize(plentiful());
  ASSERT_EQ(w.movePot(0, 2.0, 2.0), MoveOutcome::Moved);
  ASSERT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.0), AddOutcome::Queued);
  EXPECT_FALSE(w.pot(0).ingredient.has_value());
  EXPECT_EQ(w.stock(Ingredient::Salt), 15.0);
  const auto added = w.tick();
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(w.pot(0).ingredient, Ingredient::Salt);
  EXPECT_EQ(w.pot(0).quantity, 1.0);
  EXPECT_EQ(w.pot(0).temperatureTicks, 0);
  EXPECT_EQ(w.pot(0).startTick, 0);
  EXPECT_EQ(w.stock(Ingredient::Salt), 14.0);
  EXPECT_EQ(w.mealTicks(), 1);
}

TEST(CookingWorld, AdditionToNonEmptyPotIsRefused) {
  CookingWorld w;
  w.reinitialize(plentiful());
  ASSERT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.0), AddOutcome::Queued);
  // Already queued for this pot in this tick.
  EXPECT_EQ(w.queueAddition(Ingredient::Pepper, 0, 1.0), AddOutcome::PotNotEmpty);
  w.tick();
  EXPECT_EQ(w.queueAddition(Ingredient::Pepper, 0, 1.0), AddOutcome::PotNotEmpty);
  EXPECT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.0), AddOutcome::PotNotEmpty);
  w.tick();
  EXPECT_EQ(w.pot(0).ingredient, Ingredient::Salt);
  EXPECT_EQ(w.stock(Ingredient::Pepper), 15.0);
}

TEST(CookingWorld, AdditionOverStockIsRefused) {
  CookingWorld w;
  w.reinitialize(Stock{1.5, 15.0, 15.0, 15.0});
  EXPECT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.6), AddOutcome::NotEnoughStock);
  ASSERT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.0), AddOutcome::Queued);
  // The queued addition already claims 1.0 of the 1.5.
  EXPECT_EQ(w.queueAddition(Ingredient::Salt, 1, 0.6), AddOutcome::NotEnoughStock);
  EXPECT_EQ(w.queueAddition(Ingredient::Salt, 1, 0.5), AddOutcome::Queued);
  w.tick();
  EXPECT_EQ(w.stock(Ingredient::Salt), 0.0);
  EXPECT_EQ(w.queueAddition(Ingredient::Salt, 2, 0.1), AddOutcome::NotEnoughStock);
  EXPECT_EQ(w.queueAddition(Ingredient::Sugar, 2, 0.0), AddOutcome::BadQuantity);
  EXPECT_EQ(w.queueAddition(Ingredient::Sugar, 2, -1.0), AddOutcome::BadQuantity);
  EXPECT_EQ(w.queueAddition(Ingredient::Sugar, 7, 1.0), AddOutcome::NoSuchPot);
}

TEST(CookingWorld, HeatsOneTickPerTickOnStove) {
  CookingWorld w;
  w.reinitialize(plentiful());
  ASSERT_EQ(w.movePot(0, 2.0, 2.0), MoveOutcome::Moved);
  ASSERT_EQ(w.movePot(2, 6.0, 6.0), MoveOutcome::Moved);  // stays empty
  w.queueAddition(Ingredient::Salt, 0, 1.0);
  w.tick();  // added at 0 ticks; heats from the next tick on
  for (int t = 1; t <= 30; ++t) {
    w.tick();
    EXPECT_EQ(w.pot(0).temperatureTicks, t);
  }
  EXPECT_EQ(ticksToTemperature(w.pot(0).temperatureTicks), 3.0);
  EXPECT_EQ(w.pot(2).temperatureTicks, 0);  // an empty pot does not heat
}

TEST(CookingWorld, CoolsOneTickPerTickOffStoveFlooredAtZero) {
  CookingWorld w;
  w.reinitialize(plentiful());
  ASSERT_EQ(w.movePot(0, 2.0, 2.0), MoveOutcome::Moved);
  w.queueAddition(Ingredient::Salt, 0, 1.0);
  for (int t = 0; t < 4; ++t) w.tick();
  ASSERT_EQ(w.pot(0).temperatureTicks, 3);
  ASSERT_TRUE(w.removeFromStove(0));
  w.tick();
  EXPECT_EQ(w.pot(0).temperatureTicks, 2);
  w.tick();
  w.tick();
  EXPECT_EQ(w.pot(0).temperatureTicks, 0);
  w.tick();
  EXPECT_EQ(w.pot(0).temperatureTicks, 0);
  // An addition to a pot that is off the stove stays at 0.
  w.queueAddition(Ingredient::Pepper, 3, 1.0);
  w.tick();
  w.tick();
  EXPECT_EQ(w.pot(3).temperatureTicks, 0);
}

TEST(CookingWorld, ServedTicksAreTotalMinusStartMinusOne) {
  for (int start = 0; start < 5; ++start) {
    for (int total = start + 1; total < 40; total += 7) {
      CookingWorld w;
      w.reinitialize(plentiful());
      ASSERT_EQ(w.movePot(0, 2.0, 2.0), MoveOutcome::Moved);
      for (int t = 0; t < total; ++t) {
        if (t == start) {
          ASSERT_EQ(w.queueAddition(Ingredient::Salt, 0, 1.0), AddOutcome::Queued);
        }
        w.tick();
      }
      ASSERT_EQ(w.mealTicks(), total);
      ASSERT_EQ(w.pot(0).startTick, start);
      EXPECT_EQ(w.pot(0).temperatureTicks, std::max(0, total - start - 1)) << start << " " << total;
    }
  }
}

TEST(CookingWorld, ReinitializeClearsEverything) {
  CookingWorld w;
  w.reinitialize(plentiful());
  w.movePot(0, 2.0, 2.0);
  w.queueAddition(Ingredient::Salt, 0, 1.0);
  w.tick();
  w.queueAddition(Ingredient::Pepper, 1, 1.0);
  w.reinitialize(Stock{11, 12, 13, 14});
  EXPECT_FALSE(w.pot(0).onStove);
  EXPECT_FALSE(w.pot(0).ingredient.has_value());
  EXPECT_TRUE(w.queuedAdditions().empty());
  EXPECT_TRUE(w.contents().empty());
  EXPECT_EQ(w.mealTicks(), 0);
  EXPECT_EQ(w.stock(Ingredient::Flour), 14.0);
}

}  // namespace
