// Fixtures (mocap bodies a scenario positions) and the ray-based support check, on the feeding scene's two tables.
#include "robot/world/Clearance.h"
#include "robot/world/Support.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <cmath>

namespace cbtl::world {
namespace {

// The feeding scene's tables stand centred here (feeding.xml); the round one has radius 0.32 m.
const Eigen::Vector3d kTableCentre(0.3505, 0.4495, 0.0);
constexpr double kRoundRadius = 0.32, kPlateRadius = 0.149;

Pose3 platePoseAt(const Workspace& ws, double x, double y) {
  Pose3 p = *ws.objectPose("plate");
  p.position.x() = x;
  p.position.y() = y;
  return p;
}

// Puts the round table where the rectangular one stood and parks the rectangular one where the round one was.
void useRoundTable(Workspace& ws) {
  const Pose3 inUse = ws.state().fixtures.at("table"), parked = ws.state().fixtures.at("table_round");
  ASSERT_EQ(ws.setFixturePose("table", parked), StateStatus::Ok);
  ASSERT_EQ(ws.setFixturePose("table_round", inUse), StateStatus::Ok);
}

TEST(WorldFixtures, TheFeedingTablesAreFixturesWithTheirPosesInTheState) {
  const auto scene = test::feedingScene();
  ASSERT_EQ(scene->fixtures().size(), 4u);  // the two tables, and the friend and the TV of a meal's setting
  EXPECT_GE(scene->fixtureIndex("table"), 0);
  EXPECT_GE(scene->fixtureIndex("table_round"), 0);
  EXPECT_GE(scene->fixtureIndex("friend"), 0);
  EXPECT_GE(scene->fixtureIndex("tv"), 0);
  EXPECT_EQ(scene->fixtureIndex("plate"), -1);
  EXPECT_EQ(scene->objectIndex("table"), -1);  // not a movable object
  EXPECT_EQ(scene->bodyKind(scene->bodyId("table_round")), BodyKind::Scenery);
  Workspace ws(scene);
  EXPECT_NEAR((ws.state().fixtures.at("table").position - kTableCentre).norm(), 0.0, 1e-9);
  EXPECT_NEAR(ws.state().fixtures.at("table_round").position.z(), -3.0, 1e-9);
}

TEST(WorldFixtures, MovingAFixtureMovesItsGeomsAndSetStateRestoresThem) {
  Workspace ws(test::feedingScene());
  const WorldState before = ws.state();
  const int top = ws.scene().geomId("table_round_top");
  ASSERT_GE(top, 0);
  useRoundTable(ws);
  EXPECT_NEAR(ws.data()->geom_xpos[3 * top + 2], 0.13, 1e-9);
  EXPECT_NEAR(ws.data()->geom_xpos[3 * top], kTableCentre.x(), 1e-9);
  ws.setState(before);
  EXPECT_NEAR(ws.data()->geom_xpos[3 * top + 2], -3.0 + 0.13, 1e-9);
  WorldState unknown = before;
  unknown.fixtures["sofa"] = Pose3{};
  EXPECT_EQ(ws.setState(unknown), StateStatus::UnknownObject);
  EXPECT_EQ(ws.setFixturePose("sofa", Pose3{}), StateStatus::UnknownObject);
}

TEST(WorldFixtures, ChecksSeeTheTableInUseOnly) {
  // The drink's cup sunk into the round table's top, at a spot the rectangular top does not reach (x < 0.121).
  Workspace ws(test::feedingScene());
  ClearanceChecker clearance(test::feedingScene());
  Pose3 drink = *ws.objectPose("drink");
  drink.position = Eigen::Vector3d(0.06, 0.45, 0.12);
  const PlacementReport free = clearance.checkPlacement(ws, "drink", drink);
  EXPECT_TRUE(free.ok()) << free.other;
  useRoundTable(ws);
  const PlacementReport r = clearance.checkPlacement(ws, "drink", drink);
  EXPECT_EQ(r.status, PlacementStatus::Collides);
  EXPECT_EQ(r.other, "table_round_top");
  // The robot's collision pairs include the fixtures' geoms.
  const int top = ws.scene().geomId("table_round_top");
  bool paired = false;
  for (const auto& p : ws.scene().robotPairs()) paired = paired || p.g1 == top || p.g2 == top;
  EXPECT_TRUE(paired);
}

TEST(WorldSupport, APlateStandsOnTheRectangularTableAnywhereInItsArea) {
  Workspace ws(test::feedingScene());
  for (double x : {0.30, 0.38})
    for (double y : {0.25, 0.45, 0.64}) {
      const SupportReport r = supportAt(ws, "plate", platePoseAt(ws, x, y));
      EXPECT_TRUE(r.supported()) << x << ", " << y << ": " << r.unsupportedRays << " rays miss";
      EXPECT_EQ(r.support, "table_top");
    }
}

TEST(WorldSupport, OnTheRoundTableThePlateMustKeepItsRimOverTheTop) {
  Workspace ws(test::feedingScene());
  useRoundTable(ws);
  const double inside = kRoundRadius - kPlateRadius;  // 0.171 m: farthest the centre may be from the table's
  const SupportReport centre = supportAt(ws, "plate", platePoseAt(ws, kTableCentre.x(), kTableCentre.y()));
  EXPECT_TRUE(centre.supported());
  EXPECT_EQ(centre.support, "table_round_top");
  EXPECT_TRUE(supportAt(ws, "plate", platePoseAt(ws, kTableCentre.x(), kTableCentre.y() + inside - 0.005)).supported());
  const SupportReport over =
      supportAt(ws, "plate", platePoseAt(ws, kTableCentre.x(), kTableCentre.y() + inside + 0.01));
  EXPECT_EQ(over.status, SupportStatus::Overhangs);
  EXPECT_GT(over.unsupportedRays, 0);
  // The rectangular table's corner spot of the plate area hangs over the round one.
  EXPECT_FALSE(supportAt(ws, "plate", platePoseAt(ws, 0.30, 0.25)).supported());
}

TEST(WorldSupport, TheDrinksFootprintIsItsCupNotTheHolderAboveIt) {
  // The holder reaches 13 cm behind the cup at 14 cm height; over the table's edge it does not matter.
  Workspace ws(test::feedingScene());
  Pose3 drink = *ws.objectPose("drink");
  drink.position.x() = 0.121 + 0.05;  // the cup (radius 0.0435) inside the rectangular top, the holder beyond
  drink.position.y() = 0.45;
  EXPECT_TRUE(supportAt(ws, "drink", drink).supported());
  drink.position.x() = 0.121 + 0.03;  // the cup's rim over the edge
  EXPECT_FALSE(supportAt(ws, "drink", drink).supported());
}

TEST(WorldSupport, AFloatingOrUnknownBodyIsNotSupported) {
  Workspace ws(test::feedingScene());
  Pose3 plate = platePoseAt(ws, 0.34, 0.45);
  plate.position.z() += 0.02;
  EXPECT_EQ(supportAt(ws, "plate", plate).status, SupportStatus::Overhangs);
  EXPECT_EQ(supportAt(ws, "teapot", plate).status, SupportStatus::UnknownObject);
  plate.position.x() = std::nan("");
  EXPECT_EQ(supportAt(ws, "plate", plate).status, SupportStatus::UnknownObject);
}

TEST(WorldSupport, DropDistanceIsHowFarTheBodyFallsOntoTheHighestThingUnderIt) {
  Workspace ws(test::feedingScene());
  useRoundTable(ws);
  Pose3 plate = platePoseAt(ws, 0.34, 0.45);
  const double resting = plate.position.z();  // bottom 0.5 mm above the top
  plate.position.z() = resting + 0.02;
  const auto drop = dropDistance(ws, "plate", plate, 0.03);
  ASSERT_TRUE(drop.has_value());
  EXPECT_NEAR(*drop, 0.0205, 1e-6);
  EXPECT_FALSE(dropDistance(ws, "plate", plate, 0.01).has_value());
  plate.position.y() = 1.5;  // nothing under it but the floor, 80 cm down
  EXPECT_FALSE(dropDistance(ws, "plate", plate, 0.03).has_value());
}

}  // namespace
}  // namespace cbtl::world
