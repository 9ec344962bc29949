// The world operations the simulators and the action executor build on: samplers, perception and actions on
// the feeding and home scenes.
#include "robot/world/WorldOperations.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

using namespace builtins;

TEST(WorldOperations, FeedingIkSamplerAndOcclusion) {
  World w(test::feedingScene());
  Rng rng(1);
  const Pose3 target = w.workspace().forwardKinematics(test::feedingConf("drinkGaze"));
  w.workspace().setArm(configs::kRetract);
  const auto q = sampleIk(w, target, rng);
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ(w.workspace().state().arm, configs::kRetract);  // sampling leaves the arm where it was
  EXPECT_TRUE(checkArm(w.workspace(), *q).free());
  EXPECT_LE((w.workspace().forwardKinematics(*q).position - target.position).norm(), 1e-3);
  EXPECT_FALSE(sampleIk(w, Pose3::fromPosition({3, 0, 0}), rng).has_value());
  EXPECT_EQ(occlusion(w, configs::kRetract), 0.0);
}

TEST(WorldOperations, PlacementSamplerRespectsSurfaceAndClearance) {
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
    EXPECT_GE(w.clearance().objectDistance("book_0", *pose, "book_6", *w.workspace().objectPose("book_6")), 0.1);
  }
  EXPECT_FALSE(samplePlacement(w, "book_0", "no_such_surface", 0.1, rng).has_value());
}

TEST(WorldOperations, MoveArmReleaseAndSay) {
  World w(test::feedingScene());
  Rng rng(2);
  w.workspace().setArm(configs::kRetract);
  const ActionResult m = moveArm(w, test::feedingConf("abovePlate"));
  ASSERT_TRUE(m.done()) << m.detail;
  EXPECT_EQ(m.armPath.front(), configs::kRetract);
  EXPECT_EQ(w.workspace().state().arm, test::feedingConf("abovePlate"));
  EXPECT_EQ(release(w).status, ActionStatus::NotHolding);
  EXPECT_TRUE(say(w, "Ready for a bite?").done());
  EXPECT_EQ(w.utterances().back(), "Ready for a bite?");
}

TEST(WorldOperations, GraspTheUtensilFromAboveTheMount) {
  World w(test::feedingScene());
  Rng rng(3);
  w.workspace().setArm(test::feedingConf("utensilAboveMount"));
  // 0.1 m above: too far for a grasp; the tool frame inside the mount is close enough.
  EXPECT_EQ(grasp(w, "utensil", 0.05).status, ActionStatus::OutOfReach);
  const Pose3 inside{Eigen::Vector3d(0.242, -0.077, 0.07), Eigen::Quaterniond(0, 1, 0, 0)};
  const ArmConfig above = w.workspace().state().arm;
  const IkResult ik = solveIk(w.workspace(), inside, above, rng, w.ik);
  w.workspace().setArm(above);
  ASSERT_TRUE(ik.solved());
  ASSERT_TRUE(moveArm(w, ik.q).done());
  ASSERT_TRUE(grasp(w, "utensil").done());
  EXPECT_EQ(grasp(w, "plate").status, ActionStatus::AlreadyHolding);
  const Pose3 before = *w.workspace().objectPose("utensil");
  ASSERT_TRUE(moveArm(w, test::feedingConf("utensilAboveMount")).done());
  EXPECT_GT(w.workspace().objectPose("utensil")->position.z(), before.position.z() + 0.05);  // it came along
  ASSERT_TRUE(release(w).done());
  EXPECT_EQ(w.workspace().heldObject(), -1);
}

TEST(WorldOperations, HomeBaseMoveAndGrasp) {
  World w(test::homeScene());
  Rng rng(5);
  WorldState st;
  st.arm = configs::kRetract;
  ASSERT_EQ(w.workspace().setState(st), StateStatus::Ok);
  const ActionResult base = moveBase(w, {1.0, 0.2, 0.0});
  ASSERT_TRUE(base.done()) << base.detail;
  EXPECT_NEAR(w.workspace().state().base.x, 1.0, 1e-12);
  // Hold a book (attached where it is: the test only needs something in the gripper).
  ASSERT_EQ(w.workspace().setObjectPose("book_0", w.workspace().toolPose() * Pose3::fromPosition({0, 0, 0.1})),
            StateStatus::Ok);
  ASSERT_TRUE(grasp(w, "book_0").done());
  EXPECT_EQ(w.workspace().state().held->object, "book_0");
  // Closed to the book's 4 cm (of the fingers' 4.4 cm opening), not fully (GraspClosureTest has the details).
  EXPECT_GT(w.workspace().state().gripper, 0.8);
  EXPECT_LT(w.workspace().state().gripper, 1.0);
}

TEST(WorldOperations, FailedActionLeavesTheWorldUnchanged) {
  World w(test::feedingScene());
  Rng rng(6);
  w.workspace().setArm(configs::kRetract);
  const ArmConfig inTable{-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004};  // through the table
  ASSERT_FALSE(checkArm(w.workspace(), inTable).free());
  w.workspace().setArm(configs::kRetract);
  const ActionResult r = moveArm(w, inTable);
  EXPECT_EQ(r.status, ActionStatus::NoPath);
  EXPECT_EQ(w.workspace().state().arm, configs::kRetract);
}

}  // namespace
}  // namespace cbtl::world
