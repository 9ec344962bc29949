// Feeding's grasp("drink") (domains/feeding/FeedingActions.h): the open fingers slide along the handle's sides and
// close on it, touching it within the pads' compliance; the drink is never "grasped" with the fingers short of it.
#include "domains/feeding/FeedingActions.h"
#include "robot/world/GeomDistance.h"
#include "robot/world/GraspClosure.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

namespace {

namespace feeding = cbtl::domains::feeding;
namespace world = cbtl::world;
using cbtl::sim::ActionCall;
using cbtl::sim::Value;

TEST(FeedingDrinkGrasp, TheFingersCloseOnTheHandle) {
  const auto scene = cbtl::test::programSceneOf("feeding");
  world::World w(scene);
  world::WorldState s = w.workspace().state();
  s.arm = world::configs::kRetract;
  w.workspace().setState(s);
  const auto actions = feeding::FeedingActions::forScene(*scene);
  const auto r =
      actions->execute(w, ActionCall{"grasp", {Value::name("drink")}}, cbtl::actions::ExecutionMode::Execute);
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->done()) << r->detail;
  const world::Workspace& ws = w.workspace();
  const int drink = scene->objectIndex("drink");
  ASSERT_EQ(ws.heldObject(), drink);
  const world::GripperContact grip = world::gripperContact(ws, drink);
  EXPECT_EQ(scene->geomName(grip.objectGeom), "drink_holder");
  EXPECT_LE(grip.separation, 0.0);                       // the pads touch the handle...
  EXPECT_GE(grip.separation, -world::kGraspCompliance);  // ...within their compliance
  EXPECT_GT(ws.state().gripper, 0.0);                    // closed to the handle's width, not fully
  EXPECT_LT(ws.state().gripper, 1.0);
  // Both fingers touch it (a parallel grip, not one finger pressing the handle against nothing).
  for (const char* finger : {"left_finger_geom", "right_finger_geom"}) {
    const double sep =
        scene->geomDistance().separation(ws.data(), scene->geomId(finger), scene->geomId("drink_holder"));
    EXPECT_LE(sep, 0.0) << finger;
    EXPECT_GE(sep, -world::kGraspCompliance) << finger;
  }
}

}  // namespace
