// The built-ins the language binds: predicates, samplers and actions on the feeding and home scenes.
#include "robot/world/WorldOperations.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

using namespace builtins;

TEST(WorldBuiltins, PoseHelpers) {
  const Pose3 a{Eigen::Vector3d(1, 2, 3), Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()))};
  const Pose3 b{Eigen::Vector3d(-1, 0.5, 2), Eigen::Quaterniond(Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX()))};
  EXPECT_NEAR(poseAbove(a, 0.08).position.z(), 3.08, 1e-12);
  const Pose3 rel = relativePose(a, b);
  const Pose3 back = composePose(a, rel);
  EXPECT_NEAR((back.position - b.position).norm(), 0.0, 1e-12);
  EXPECT_NEAR(rotationDistance(back.orientation, b.orientation), 0.0, 1e-7);
  EXPECT_NEAR(distance(a, b), std::sqrt(4 + 2.25 + 1), 1e-12);
}

TEST(WorldBuiltins, FeedingPredicates) {
  World w(test::feedingScene());
  Rng rng(1);
  EXPECT_TRUE(collisionFreeConf(w, configs::kRetract));
  EXPECT_FALSE(collisionFreeConf(w, {-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004}));
  EXPECT_FALSE(collisionFreeConf(w, {0, 3.0, 0, 0, 0, 0, 0}));
  const Pose3 plate = Pose3::fromPosition({0.34, 0.30, 0.1625});
  EXPECT_TRUE(collisionFreePoses(w, "plate", plate, "drink", Pose3::fromPosition({0.34, 0.65, 0.15})));
  EXPECT_FALSE(collisionFreePoses(w, "plate", plate, "drink", Pose3::fromPosition({0.34, 0.40, 0.15})));
  EXPECT_TRUE(ikFeasible(w, forwardKinematics(w, configs::kAbovePlate), rng));
  EXPECT_FALSE(ikFeasible(w, Pose3::fromPosition({3, 0, 0}), rng));
  const auto q = sampleIk(w, forwardKinematics(w, configs::kDrinkGaze), rng);
  ASSERT_TRUE(q.has_value());
  EXPECT_TRUE(collisionFreeConf(w, *q));
  EXPECT_EQ(occlusion(w, configs::kRetract), 0.0);
  EXPECT_TRUE(motionFeasible(w, configs::kRetract, configs::kAbovePlate, rng));
}

TEST(WorldBuiltins, PlacementSamplerRespectsSurfaceAndClearance) {
  World w(test::homeScene());
  Rng rng(4);
  // With the duster lying on the main table there is no spot 0.1 m away from it.
  EXPECT_FALSE(samplePlacement(w, "book_0", "table_top", 0.1, rng, 50).has_value());
  ASSERT_EQ(w.workspace().setObjectPose("duster", Pose3::fromPosition({-0.75, -0.95, 0.3})), StateStatus::Ok);
  for (int i = 0; i < 5; ++i) {
    const auto pose = samplePlacement(w, "book_0", "table_top", 0.1, rng);
    ASSERT_TRUE(pose.has_value());
    EXPECT_NEAR(pose->position.z(), 0.08, 1e-9);          // resting on the table top (z = 0)
    EXPECT_LE(std::abs(pose->position.x() + 0.75), 0.1);  // over the table
    EXPECT_LE(std::abs(pose->position.y()), 0.3);
    EXPECT_TRUE(placementClear(w, "book_0", *pose, 0.1));
    // 0.1 m from the book on the nearest side table.
    EXPECT_GE(objectDistance(w, "book_0", *pose, "book_6", *objectPose(w, "book_6")), 0.1);
  }
  EXPECT_FALSE(samplePlacement(w, "book_0", "no_such_surface", 0.1, rng).has_value());
}

TEST(WorldBuiltins, FeedingActionsMoveTheWorld) {
  World w(test::feedingScene());
  Rng rng(2);
  w.workspace().setArm(configs::kRetract);
  ASSERT_TRUE(movePlate(w, 0.36, 0.40).done());
  EXPECT_NEAR(objectPose(w, "plate")->position.y(), 0.40, 1e-12);
  EXPECT_EQ(moveDrink(w, 0.36, 0.45).status, ActionStatus::Blocked);  // onto the plate
  EXPECT_NEAR(objectPose(w, "drink")->position.y(), 0.565, 1e-12);    // unchanged
  const ActionResult m = moveArm(w, configs::kAbovePlate, rng);
  ASSERT_TRUE(m.done()) << m.detail;
  EXPECT_EQ(m.armPath.front(), configs::kRetract);
  EXPECT_EQ(w.workspace().state().arm, configs::kAbovePlate);
  EXPECT_EQ(release(w).status, ActionStatus::NotHolding);
  EXPECT_TRUE(say(w, "Ready for a bite?").done());
  EXPECT_EQ(w.utterances().back(), "Ready for a bite?");
}

TEST(WorldBuiltins, GraspTheUtensilFromAboveTheMount) {
  World w(test::feedingScene());
  Rng rng(3);
  w.workspace().setArm(configs::kUtensilAboveMount);
  // 0.1 m above: too far for a grasp; the tool frame inside the mount is close enough.
  EXPECT_EQ(grasp(w, "utensil", 0.05).status, ActionStatus::OutOfReach);
  const Pose3 inside{Eigen::Vector3d(0.242, -0.077, 0.07), Eigen::Quaterniond(0, 1, 0, 0)};
  ASSERT_TRUE(moveArmToPose(w, inside, rng).done());
  ASSERT_TRUE(grasp(w, "utensil").done());
  EXPECT_EQ(grasp(w, "plate").status, ActionStatus::AlreadyHolding);
  const Pose3 before = *objectPose(w, "utensil");
  ASSERT_TRUE(moveArm(w, configs::kUtensilAboveMount, rng).done());
  EXPECT_GT(objectPose(w, "utensil")->position.z(), before.position.z() + 0.05);  // it came along
  ASSERT_TRUE(release(w).done());
  EXPECT_EQ(w.workspace().heldObject(), -1);
}

TEST(WorldBuiltins, HomeActionsBaseHandoverWipe) {
  World w(test::homeScene());
  Rng rng(5);
  WorldState st;
  st.arm = configs::kRetract;
  ASSERT_EQ(w.workspace().setState(st), StateStatus::Ok);
  EXPECT_EQ(handOver(w, {1.33, 0.11, 0.52}, rng).status, ActionStatus::NotHolding);
  const ActionResult base = moveBase(w, {1.0, 0.2, 0.0}, rng);
  ASSERT_TRUE(base.done()) << base.detail;
  EXPECT_NEAR(w.workspace().state().base.x, 1.0, 1e-12);
  // Hold a book (attached where it is: the test only needs something in the gripper) and hand it over.
  ASSERT_EQ(w.workspace().setObjectPose("book_0", w.workspace().toolPose() * Pose3::fromPosition({0, 0, 0.1})),
            StateStatus::Ok);
  ASSERT_TRUE(grasp(w, "book_0").done());
  const ActionResult h = handOver(w, {1.33, 0.11, 0.52}, rng);
  ASSERT_TRUE(h.done()) << toString(h.status) << " " << h.detail;
  EXPECT_NEAR((toolPose(w).position - Eigen::Vector3d(1.33, 0.11, 0.52)).norm(), 0.0, 2e-3);
  EXPECT_EQ(w.utterances().back(), "Here you go!");
  EXPECT_EQ(wipe(w, "no_such_surface", rng).status, ActionStatus::InvalidArgument);
}

TEST(WorldBuiltins, WipeASideTableWithTheDuster) {
  World w(test::homeScene());
  Rng rng(7);
  WorldState st;
  st.arm = configs::kHome;
  st.base = {-0.35, -0.45, 0.0};
  ASSERT_EQ(w.workspace().setState(st), StateStatus::Ok);
  EXPECT_EQ(wipe(w, "side_table_0_top", rng).status, ActionStatus::NotHolding);
  ASSERT_EQ(w.workspace().setObjectPose("duster", toolPose(w) * Pose3::fromPosition({0, 0, 0.05})), StateStatus::Ok);
  ASSERT_TRUE(grasp(w, "duster").done());
  ASSERT_TRUE(checkRobotCollisions(w.workspace()).free()) << checkRobotCollisions(w.workspace()).first;
  // The book lying on the side table is in the way of a low pass; wipe above it.
  const ActionResult r = wipe(w, "side_table_0_top", rng, 0.35);
  ASSERT_TRUE(r.done()) << toString(r.status) << " " << r.detail;
  EXPECT_GE(r.armPath.size(), 5U);  // start + 2 passes x 2 ends
  // Every executed segment is collision-free with the duster in hand.
  for (std::size_t i = 1; i < r.armPath.size(); ++i)
    EXPECT_TRUE(armSegmentFree(w.workspace(), r.armPath[i - 1], r.armPath[i], 0.005));
}

TEST(WorldBuiltins, FailedActionLeavesTheWorldUnchanged) {
  World w(test::feedingScene());
  Rng rng(6);
  w.workspace().setArm(configs::kRetract);
  const ActionResult r = moveArmToPose(w, Pose3::fromPosition({3, 0, 0.5}), rng);
  EXPECT_EQ(r.status, ActionStatus::NoIk);
  EXPECT_EQ(w.workspace().state().arm, configs::kRetract);
}

}  // namespace
}  // namespace cbtl::world
