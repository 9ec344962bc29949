// The wiping sweep: from a pre-wipe pose the duster covers a reachable surface and the base comes back;
// without the duster on the surface, or without anything held, the sweep fails and nothing moves.
#include "robot/actions/CallArguments.h"
#include "robot/actions/RobotActions.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/actions/WipeSweep.h"
#include "robot/world/Separation.h"
#include "tests/unit/domains/HomeTestSupport.h"

#include <gtest/gtest.h>

#include <random>

namespace {

namespace actions = cbtl::actions;
namespace home = cbtl::domains::home;
namespace world = cbtl::world;
using cbtl::sim::ActionCall;
using cbtl::sim::Value;
using cbtl::world::builtins::ActionStatus;

class WipeSweepTest : public ::testing::Test {
 protected:
  WipeSweepTest() : w(cbtl::test::homeScene()), rng(5) {}

  // The robot at `base` holding the duster (standard grasp) with the arm at a collision-free IK solution of
  // the pre-wipe pose of `surface`; false when none is found.
  bool readyToWipe(const std::string& surface, const world::Pose2& base) {
    world::WorldState s = w.workspace().state();
    s.base = base;
    s.arm = world::configs::kHome;
    s.held = world::Grasp{"duster", actions::dusterToolInBody().inverse()};
    for (int k = 0; k < 9; ++k) s.objects["book_" + std::to_string(k)] = home::parkedPose(static_cast<std::size_t>(k));
    if (w.workspace().setState(s) != world::StateStatus::Ok) return false;
    const auto tool = actions::preWipeToolPose(w, surface, "duster", s.held->toolToObject, base);
    if (!tool) return false;
    for (int attempt = 0; attempt < 5; ++attempt) {
      if (const auto q = world::builtins::sampleIk(w, *tool, rng)) {
        w.workspace().setArm(*q);
        return true;
      }
    }
    return false;
  }

  world::World w;
  world::Rng rng{std::mt19937_64::default_seed};  // the stream these tests were written with
  actions::RobotActions actions;
};

TEST_F(WipeSweepTest, WipesEveryHomeSurfaceFromItsApproachBase) {
  const std::vector<std::pair<std::string, world::Pose2>> cases{
      {"shelf_layer_1", {0, 0, 0}}, {"shelf_layer_2", {0, 0, 0}},        {"shelf_layer_0", {0.067, 0.023, 0}},
      {"table_top", {0, -0.1, 0}},  {"side_table_0_top", {0, -0.55, 0}}, {"side_table_2_top", {0, -1.05, 0}}};
  for (const auto& [surface, base] : cases) {
    SCOPED_TRACE(surface);
    ASSERT_TRUE(readyToWipe(surface, base));
    const world::ArmConfig arm = w.workspace().state().arm;
    // The sweep may touch the face, as the skill's `allow held touch ... 5 mm` does.
    world::ContactAllowance touch;
    touch.geom = w.workspace().scene().geomId(surface);
    touch.separation = -0.005;
    w.planning.collision.allowances = {touch};
    w.setRecording(true);
    w.takeMotions();
    const auto r =
        actions.execute(w, ActionCall{"wipe", {Value::name(surface), Value::vec({base.x, base.y, base.yaw})}});
    w.setRecording(false);
    w.planning.collision.allowances.clear();
    ASSERT_TRUE(r.has_value());
    ASSERT_TRUE(r->done()) << r->detail;
    EXPECT_GE(r->basePath.size(), 3u);  // at least one stroke there and back, plus the return
    EXPECT_NEAR(w.workspace().state().base.x, base.x, 1e-9);
    EXPECT_NEAR(w.workspace().state().base.y, base.y, 1e-9);
    EXPECT_EQ(w.workspace().state().arm, arm);  // down to the face and back up the same way
    // Every stroke runs with the duster on the face: touching it, pressed in by at most the allowed 5 mm.
    int strokes = 0;
    for (const world::ExecutedMotion& m : w.takeMotions()) {
      if (m.kind != world::ExecutedMotion::Kind::Base) continue;
      ++strokes;
      ASSERT_EQ(w.workspace().setState(m.start), world::StateStatus::Ok);
      const double head =
          world::exactSeparation(w.workspace(), w.workspace().scene().geomId("duster_head"), touch.geom);
      EXPECT_LE(head, 0.0) << "stroke " << strokes;
      EXPECT_GE(head, -0.005) << "stroke " << strokes;
    }
    EXPECT_GE(strokes, 2);
  }
}

TEST_F(WipeSweepTest, FailsWhenTheDusterIsNotOnTheSurface) {
  ASSERT_TRUE(readyToWipe("shelf_layer_1", {0, 0, 0}));
  const auto r = actions.execute(w, ActionCall{"wipe", {Value::name("shelf_layer_2"), Value::vec({0, 0, 0})}});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, ActionStatus::OutOfReach);
  const auto unknown = actions.execute(w, ActionCall{"wipe", {Value::name("ceiling"), Value::vec({0, 0, 0})}});
  EXPECT_EQ(unknown->status, ActionStatus::InvalidArgument);
}

TEST_F(WipeSweepTest, FailsWithoutAHeldTool) {
  const auto r = actions.execute(w, ActionCall{"wipe", {Value::name("table_top"), Value::vec({0, -0.1, 0})}});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, ActionStatus::NotHolding);
}

TEST_F(WipeSweepTest, ABlockedSweepLeavesTheWorldAsItWas) {
  ASSERT_TRUE(readyToWipe("shelf_layer_1", {0, 0, 0}));
  // A book standing in the middle of the middle layer is in the duster's way.
  w.workspace().setObjectPose("book_0", world::Pose3::fromPosition(Eigen::Vector3d(-0.2, 0.675, 0.13)));
  const world::WorldState before = w.workspace().state();
  ActionCall call{"wipe", {Value::name("shelf_layer_1"), Value::vec({0, 0, 0})}};
  call.exceptions.push_back({"held", {"shelf_layer_1"}, -0.005, "cleaning.cbtl:137:5"});
  const auto r = actions.execute(w, call);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, ActionStatus::NoPath) << r->detail;
  EXPECT_EQ(w.workspace().state().base.x, before.base.x);
  EXPECT_EQ(w.workspace().state().arm, before.arm);
}

// The duster touches what it wipes: a call without the skill's `allow` for that contact is refused, and says what
// to declare.
TEST_F(WipeSweepTest, AWipeWithoutAnAllowForTheSurfaceIsRefused) {
  ASSERT_TRUE(readyToWipe("shelf_layer_1", {0, 0, 0}));
  const world::WorldState before = w.workspace().state();
  const auto r = actions.execute(w, ActionCall{"wipe", {Value::name("shelf_layer_1"), Value::vec({0, 0, 0})}});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, ActionStatus::Blocked);
  EXPECT_NE(r->detail.find("allow held touch \"shelf_layer_1\""), std::string::npos) << r->detail;
  EXPECT_EQ(w.workspace().state().arm, before.arm);
}

}  // namespace
