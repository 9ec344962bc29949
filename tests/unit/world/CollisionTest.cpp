// Known colliding and free states of the arm, its held object and the mobile base.
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace cbtl::world {
namespace {

TEST(WorldCollision, NamedFeedingConfigurationsAreFree) {
  Workspace ws(test::feedingScene());
  for (const auto& q : {configs::kRetract, configs::kHome, test::feedingConf("abovePlate"),
                        test::feedingConf("drinkGaze"), configs::kZero}) {
    const auto r = checkArm(ws, q);
    EXPECT_TRUE(r.free()) << toString(r.status) << " " << r.first << " / " << r.second;
  }
}

TEST(WorldCollision, ArmThroughTableCollides) {
  Workspace ws(test::feedingScene());
  // The gripper pushed 2.5 cm into the table top (found by IK to a tool target below the table top).
  const ArmConfig q{-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004};
  const auto r = checkArm(ws, q);
  EXPECT_EQ(r.status, CollisionStatus::RobotWorld) << r.first << " / " << r.second;
  EXPECT_GT(r.depth, 0.0);
}

TEST(WorldCollision, ArmFoldedIntoItselfIsSelfCollision) {
  Workspace ws(test::feedingScene());
  const ArmConfig q{0, 0, 0, 2.6, 0, 2.2, 0};
  const auto r = checkArm(ws, q);
  EXPECT_EQ(r.status, CollisionStatus::SelfCollision) << toString(r.status) << " " << r.first << " / " << r.second;
}

TEST(WorldCollision, HeldObjectIsChecked) {
  Workspace ws(test::feedingScene());
  // Tool 0.25 m above the table top, pointing down; the drink held 0.2 m past the tool reaches into the table.
  const ArmConfig above{-0.7673, 0.7097, 2.6987, -0.6445, 0.2934, -1.8253, -1.0358};
  ws.setArm(above);
  ASSERT_TRUE(checkRobotCollisions(ws).free());
  ASSERT_EQ(ws.setObjectPose("drink", ws.toolPose() * Pose3::fromPosition({0, 0, 0.2})), StateStatus::Ok);
  ASSERT_EQ(ws.setHeld(std::string("drink")), StateStatus::Ok);
  const auto r = checkRobotCollisions(ws);
  EXPECT_EQ(r.status, CollisionStatus::HeldObject) << toString(r.status) << " " << r.first << " / " << r.second;
  // The held object follows the arm: in the home configuration it is clear of everything.
  ws.setArm(configs::kHome);
  EXPECT_TRUE(checkRobotCollisions(ws).free()) << checkRobotCollisions(ws).first;
  ASSERT_EQ(ws.setHeld(std::nullopt), StateStatus::Ok);
  EXPECT_TRUE(checkRobotCollisions(ws).free());
}

// feeding.xml gives the fork a 5 mm keep-out distance from the head with a <pair>, where the head's own margin keeps
// everything else 2 cm away. The utensil is held (robot at home, far from the user) with its fork tip `gap` metres
// from the head sphere, the fork pointing away from the head.
CollisionReport forkNearHead(double gap) {
  Workspace ws(test::feedingScene());
  ws.setArm(configs::kHome);
  const Eigen::Vector3d head = ws.bodyPose(ws.scene().bodyId("user_head")).position;
  const Eigen::Quaterniond yawPi(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d tipLocal(0.2251, -0.002, -0.0645);  // feeding.xml's utensil_tip
  const double headRadius = 0.11, forkRadius = 0.006;
  const Eigen::Vector3d tip = head + Eigen::Vector3d(headRadius + forkRadius + gap, 0, 0);
  EXPECT_EQ(ws.setObjectPose("utensil", Pose3{tip - yawPi * tipLocal, yawPi}), StateStatus::Ok);
  EXPECT_EQ(ws.setHeld(std::string("utensil")), StateStatus::Ok);
  return checkRobotCollisions(ws);
}

TEST(WorldCollision, PairMarginGivesTheForkItsOwnKeepOutDistance) {
  EXPECT_TRUE(forkNearHead(0.008).free()) << forkNearHead(0.008).second;
  const auto close = forkNearHead(0.003);
  EXPECT_EQ(close.status, CollisionStatus::HeldObject);
  EXPECT_EQ(std::minmax(close.first, close.second),
            std::minmax(std::string("utensil_fork"), std::string("user_head_geom")));
  EXPECT_NEAR(close.depth, 0.002, 2e-4);
}

TEST(WorldCollision, MobileBaseIntoShelfCollides) {
  Workspace ws(test::homeScene());
  WorldState st;
  st.arm = configs::kRetract;
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  EXPECT_TRUE(checkRobotCollisions(ws).free()) << checkRobotCollisions(ws).first;
  st.base = {0.0, 0.62, 0.0};
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  EXPECT_EQ(checkRobotCollisions(ws).status, CollisionStatus::RobotWorld);
}

}  // namespace
}  // namespace cbtl::world
