// Placement and clearance checks with FCL.
#include "robot/world/Clearance.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

TEST(WorldClearance, DefaultFeedingPlacementsAreClear) {
  Workspace ws(test::feedingScene());
  ClearanceChecker cc(test::feedingScene());
  const auto plate = *ws.objectPose("plate");
  PlacementOptions o;
  o.clearance = 0.0;
  const auto r = cc.checkPlacement(ws, "plate", plate, o);
  EXPECT_TRUE(r.ok()) << toString(r.status) << " " << r.other << " " << r.distance;
}

TEST(WorldClearance, PlateDrinkDistanceIsExact) {
  Workspace ws(test::feedingScene());
  ClearanceChecker cc(test::feedingScene());
  // Plate (cylinder r 0.149) and drink cup (cylinder r 0.0435) side by side along y, both upright.
  const Pose3 plate = Pose3::fromPosition({0.34, 0.30, 0.1625});
  const Pose3 drink = Pose3::fromPosition({0.34, 0.60, 0.15});
  // Cup surface to plate rim: 0.30 - 0.149 - 0.0435; the holder is further away (along -x, offset in z).
  EXPECT_NEAR(cc.objectDistance("plate", plate, "drink", drink), 0.30 - 0.149 - 0.0435, 2e-3);
  EXPECT_EQ(cc.objectDistance("plate", plate, "drink", Pose3::fromPosition({0.34, 0.35, 0.15})), 0.0);
  EXPECT_LT(cc.objectDistance("plate", plate, "teapot", drink), 0.0);
}

TEST(WorldClearance, PlacementNeedsClearanceFromOtherObjects) {
  Workspace ws(test::homeScene());
  ClearanceChecker cc(test::homeScene());
  // Book 0 moved next to book 1 on the middle shelf: clear of the shelf, too close to book 1.
  const Pose3 near = Pose3::fromPosition({-0.06, 0.75, 0.13});
  const auto tooClose = cc.checkPlacement(ws, "book_0", near);
  EXPECT_EQ(tooClose.status, PlacementStatus::TooClose) << tooClose.other << " " << tooClose.distance;
  EXPECT_EQ(tooClose.other, "book_1");
  EXPECT_NEAR(tooClose.distance, 0.06 - 0.04, 1e-6);
  // With 0.1 m clearance an empty spot on the side table far from everything is fine...
  ws.setObjectPose("book_6", Pose3::fromPosition({5, 5, 5}));
  const auto ok = cc.checkPlacement(ws, "book_0", Pose3::fromPosition({-0.75, -0.45, 0.08}));
  EXPECT_TRUE(ok.ok()) << toString(ok.status) << " " << ok.other;
  // ...but sinking into the table top collides.
  const auto sunk = cc.checkPlacement(ws, "book_0", Pose3::fromPosition({-0.75, -0.45, 0.05}));
  EXPECT_EQ(sunk.status, PlacementStatus::Collides);
  EXPECT_EQ(sunk.other, "side_table_0_top");
}

TEST(WorldClearance, ObjectBoxesComeFromTheGeoms) {
  Workspace ws(test::homeScene());
  ClearanceChecker cc(test::homeScene());
  const auto box = cc.objectBox("book_3");
  ASSERT_TRUE(box.has_value());
  EXPECT_NEAR(box->halfExtents.x(), 0.02, 1e-9);
  EXPECT_NEAR(box->halfExtents.z(), 0.08, 1e-9);
  EXPECT_FALSE(cc.objectBox("nothing").has_value());
}

}  // namespace
}  // namespace cbtl::world
