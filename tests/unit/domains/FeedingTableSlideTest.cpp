// Feeding's movePlate / moveDrink (domains/feeding/TableSlide.h): the caregiver slides a body over the table.
#include "domains/feeding/FeedingSimulator.h"
#include "domains/feeding/TableSlide.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <limits>

namespace {

using cbtl::domains::feeding::isTableSlide;
using cbtl::domains::feeding::slideOnTable;
using cbtl::sim::ActionCall;
using cbtl::sim::Value;
using cbtl::world::builtins::ActionStatus;
namespace world = cbtl::world;

TEST(FeedingTableSlide, SlidesThePlateAndRefusesToStackTheDrinkOnIt) {
  world::World w(cbtl::test::programSceneOf("feeding"));
  const world::Pose3 plate = *w.workspace().objectPose("plate");
  const auto moved = slideOnTable(w, ActionCall{"movePlate", {Value::vec({0.36, 0.40})}});
  ASSERT_TRUE(moved.done()) << moved.detail;
  EXPECT_EQ(moved.steps, 1);
  const world::Pose3 after = *w.workspace().objectPose("plate");
  EXPECT_NEAR(after.position.x(), 0.36, 1e-12);
  EXPECT_NEAR(after.position.y(), 0.40, 1e-12);
  EXPECT_NEAR(after.position.z(), plate.position.z(), 1e-12);  // height and orientation kept
  EXPECT_NEAR(after.orientation.angularDistance(plate.orientation), 0.0, 1e-12);

  const world::Pose3 drink = *w.workspace().objectPose("drink");
  const auto blocked = slideOnTable(w, ActionCall{"moveDrink", {Value::vec({0.36, 0.45})}});  // onto the plate
  EXPECT_EQ(blocked.status, ActionStatus::Blocked);
  EXPECT_NE(blocked.detail.find("plate"), std::string::npos) << blocked.detail;
  EXPECT_EQ(blocked.steps, 1);
  EXPECT_EQ(w.workspace().objectPose("drink")->position, drink.position);  // unchanged
}

TEST(FeedingTableSlide, RefusesASpotWhereThePlateWouldHangOverTheRoundTable) {
  world::World w(cbtl::test::programSceneOf("feeding"));
  world::Workspace& ws = w.workspace();
  const world::Pose3 inUse = ws.state().fixtures.at("table"), parked = ws.state().fixtures.at("table_round");
  ws.setFixturePose("table", parked);
  ws.setFixturePose("table_round", inUse);
  const world::Pose3 plate = *ws.objectPose("plate");
  // (0.30, 0.25) is inside the plate's area and on the rectangular table; the round one (radius 0.32 m) ends
  // under the plate's rim.
  const auto over = slideOnTable(w, ActionCall{"movePlate", {Value::vec({0.30, 0.25})}});
  EXPECT_EQ(over.status, ActionStatus::Blocked);
  EXPECT_NE(over.detail.find("would not stand on the table"), std::string::npos) << over.detail;
  EXPECT_EQ(ws.objectPose("plate")->position, plate.position);
  const auto centre = slideOnTable(w, ActionCall{"movePlate", {Value::vec({0.32, 0.36})}});  // clear of the drink
  EXPECT_TRUE(centre.done()) << centre.detail;
}

TEST(FeedingTableSlide, BadCallsChangeNothing) {
  world::World w(cbtl::test::programSceneOf("feeding"));
  const world::Pose3 plate = *w.workspace().objectPose("plate");
  const auto illFormed = slideOnTable(w, ActionCall{"movePlate", {Value::name("table")}});
  EXPECT_FALSE(illFormed.wellFormed);
  EXPECT_EQ(illFormed.steps, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto notFinite = slideOnTable(w, ActionCall{"movePlate", {Value::vec({nan, 0.4})}});
  EXPECT_TRUE(notFinite.wellFormed);
  EXPECT_EQ(notFinite.status, ActionStatus::InvalidArgument);
  EXPECT_EQ(w.workspace().objectPose("plate")->position, plate.position);
  EXPECT_TRUE(isTableSlide("moveDrink"));
  EXPECT_FALSE(isTableSlide("moveArm"));
}

}  // namespace
