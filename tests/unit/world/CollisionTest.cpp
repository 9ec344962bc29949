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

// The feeding scene with feeding.cbtl's clearance: the robot and what it holds keep 5 cm from the user.
std::shared_ptr<const Scene> feedingWithPerson() {
  static const auto scene =
      Scene::loadFile(CBTL_DOMAINS_DIR "/feeding/feeding.xml", {{"person", {"user", "user_head"}, 0.05, "test:1:1"}})
          .scene;
  return scene;
}

// The utensil held (robot at home, far from the user) with its fork tip `gap` metres from the head sphere, the fork
// pointing away from the head; checked with `options`.
CollisionReport forkNearHead(double gap, const CollisionOptions& options = {}) {
  Workspace ws(feedingWithPerson());
  ws.setArm(configs::kHome);
  const Eigen::Vector3d head = ws.bodyPose(ws.scene().bodyId("user_head")).position;
  const Eigen::Quaterniond yawPi(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d tipLocal(0.2251, -0.002, -0.0645);  // feeding.xml's utensil_tip
  const double headRadius = 0.11, forkRadius = 0.006;
  const Eigen::Vector3d tip = head + Eigen::Vector3d(headRadius + forkRadius + gap, 0, 0);
  EXPECT_EQ(ws.setObjectPose("utensil", Pose3{tip - yawPi * tipLocal, yawPi}), StateStatus::Ok);
  EXPECT_EQ(ws.setHeld(std::string("utensil")), StateStatus::Ok);
  return checkRobotCollisions(ws, options);
}

// The bite's exception: the held utensil may come to 5 mm of the head.
CollisionOptions biteException(ContactAllowance::Part part) {
  ContactAllowance a;
  a.part = part;
  a.body = feedingWithPerson()->bodyId("user_head");
  a.separation = 0.005;
  return {{a}};
}

TEST(WorldCollision, ClearanceKeepsEverythingAwayFromThePerson) {
  EXPECT_TRUE(forkNearHead(0.06).free()) << forkNearHead(0.06).describe();
  const auto near = forkNearHead(0.03);
  EXPECT_EQ(near.status, CollisionStatus::HeldObject);
  EXPECT_EQ(std::minmax(near.first, near.second),
            std::minmax(std::string("utensil_fork"), std::string("user_head_geom")));
  EXPECT_NEAR(near.depth, 0.02, 2e-4);  // 3 cm away where 5 cm are required
  EXPECT_NEAR(near.required, 0.05, 1e-12);
  EXPECT_EQ(near.clearance, "'person' (test:1:1)");
  EXPECT_NE(near.describe().find("clearance 'person' (test:1:1) needs 50.0 mm"), std::string::npos) << near.describe();
  // Without the clearance the same state is free: touching is all an undeclared pair forbids.
  Workspace plain(test::feedingScene());
  EXPECT_DOUBLE_EQ(plain.scene().keepOut(plain.scene().geomId("utensil_fork"), plain.scene().geomId("user_head_geom")),
                   0.0);
}

TEST(WorldCollision, AnExceptionIsHonouredForItsPartOnly) {
  const CollisionOptions held = biteException(ContactAllowance::Part::HeldObject);
  EXPECT_TRUE(forkNearHead(0.008, held).free()) << forkNearHead(0.008, held).describe();
  const auto tooClose = forkNearHead(0.003, held);  // the exception has a limit of its own
  EXPECT_EQ(tooClose.status, CollisionStatus::HeldObject);
  EXPECT_NEAR(tooClose.depth, 0.002, 2e-4);
  EXPECT_TRUE(tooClose.clearance.empty());
  // An exception for the gripper does not let the held fork closer; one for the whole robot neither (the held
  // object is not a robot body).
  for (const auto part : {ContactAllowance::Part::Gripper, ContactAllowance::Part::Robot}) {
    const auto refused = forkNearHead(0.008, biteException(part));
    EXPECT_EQ(refused.status, CollisionStatus::HeldObject) << toString(part);
    EXPECT_NEAR(refused.required, 0.05, 1e-12);
  }
}

TEST(WorldCollision, AClearanceNamingNoBodyIsALoadError) {
  const auto r = Scene::loadFile(CBTL_DOMAINS_DIR "/feeding/feeding.xml", {{"person", {"usr"}, 0.05, "f.cbtl:3:1"}});
  EXPECT_EQ(r.status, LoadStatus::BadClearance);
  EXPECT_NE(r.message.find("clearance 'person' (f.cbtl:3:1): the scene has no body 'usr'"), std::string::npos)
      << r.message;
  const auto negative = Scene::loadFile(CBTL_DOMAINS_DIR "/feeding/feeding.xml", {{"person", {"user"}, -0.01, ""}});
  EXPECT_EQ(negative.status, LoadStatus::BadClearance);
}

// A clearance applies to every geom of the bodies it names (the home scene's shelf: its layers are geoms of one
// body), and to no other body.
TEST(WorldCollision, AClearanceReachesEveryGeomOfItsBodies) {
  const auto home = Scene::loadFile(CBTL_DOMAINS_DIR "/home/home.xml", {{"furniture", {"shelf"}, 0.02, ""}}).scene;
  ASSERT_TRUE(home);
  const int finger = home->geomId("right_finger_geom");
  for (const char* layer : {"shelf_layer_0", "shelf_layer_1", "shelf_layer_2"})
    EXPECT_DOUBLE_EQ(home->keepOut(finger, home->geomId(layer)), 0.02) << layer;
  EXPECT_DOUBLE_EQ(home->keepOut(finger, home->geomId("table_top")), 0.0);
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
