// Physical grasps: the fingers close until they touch the object (pads pressed in by the squeeze, within the
// compliance), a parallel gripper centres what it grips by a bounded push, and a grasp that closes on air or starts
// inside the object is refused — by closeOn and by the grasp action, which then leaves the world as it was.
#include "robot/world/GraspClosure.h"
#include "robot/world/WorldOperations.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <gtest/gtest.h>

namespace cbtl::world {
namespace {

constexpr double kBookThickness = 0.04;  // home.xml: book boxes are 0.02 x 0.05 x 0.08 half-sizes

class GraspClosureTest : public ::testing::Test {
 protected:
  GraspClosureTest() : w(test::homeScene()) {
    WorldState s = w.workspace().state();
    s.arm = configs::kHome;
    s.gripper = 1.0;
    w.workspace().setState(s);
    book = w.workspace().scene().objectIndex("book_0");
  }

  // Puts book_0 in the tool frame: `across` metres along the closing axis (tool x) off centre, its centre `depth`
  // metres past the tool frame along tool z; its 4 cm thickness lies along the closing axis.
  void placeBook(double across, double depth) {
    const Pose3 tool = w.workspace().toolPose();
    w.workspace().setObjectPose("book_0", tool * Pose3::fromPosition({across, 0, depth}));
  }

  // Puts the duster so that its pole crosses the gripper `across` metres off centre, 3 cm past the tool frame.
  void placePole(double across) {
    const Pose3 tool = w.workspace().toolPose();
    w.workspace().setObjectPose("duster", tool * Pose3::fromPosition({across, 0.2, 0.03 + 0.03}));
  }

  World w;
  int book = -1;
};

// The book's centre 10 cm past the tool frame: it spans 2-18 cm there, the finger pads -2-5 cm, the palm ends at
// -2.5 cm.
constexpr double kBetweenTheFingers = 0.10;

TEST_F(GraspClosureTest, TheFingersStopWhereTheyTouchTheBook) {
  placeBook(0, kBetweenTheFingers);
  const GraspClosure c = closeOn(w.workspace(), book);
  ASSERT_TRUE(c.holds()) << c.detail;
  EXPECT_NEAR(c.width, kBookThickness - 2 * kGraspSqueeze, 1e-4);
  EXPECT_NEAR(c.push, 0, 1e-4);
  EXPECT_GT(c.gripper, 0.0);  // not the fully closed gripper that used to sink 19.5 mm into every book
  EXPECT_LT(c.gripper, 1.0);
  EXPECT_EQ(w.workspace().state().gripper, 1.0);  // closeOn only measures

  ASSERT_TRUE(builtins::grasp(w, "book_0").done());
  EXPECT_EQ(w.workspace().state().gripper, c.gripper);
  const GripperContact held = gripperContact(w.workspace(), book);
  EXPECT_LE(held.separation, 0.0);                // the pads touch the book...
  EXPECT_GE(held.separation, -kGraspCompliance);  // ...and press in no further than their compliance
}

// The duster's pole (2 cm across, home.xml: along the duster's y, 3 cm below its head's centre) leaves 12 mm on either
// side in the open gripper: room to lie off centre.
TEST_F(GraspClosureTest, AnOffCentrePoleIsPushedToTheCentreWithinTheLimit) {
  placePole(0.003);
  const Pose3 before = *w.workspace().objectPose("duster");
  ASSERT_TRUE(builtins::grasp(w, "duster", 1.0).done());
  const Pose3 after = *w.workspace().objectPose("duster");
  const Pose3 tool = w.workspace().toolPose();
  // The pole is back on the gripper's axis, 3 mm from where it lay.
  EXPECT_NEAR((tool.inverse() * after).position.x(), 0.0, 1e-4);
  EXPECT_NEAR((after.position - before.position).norm(), 0.003, 1e-4);
  const GripperContact held = gripperContact(w.workspace(), w.workspace().scene().objectIndex("duster"));
  EXPECT_LE(held.separation, 0.0);
  EXPECT_GE(held.separation, -kGraspCompliance);
}

TEST_F(GraspClosureTest, APoleTooFarOffCentreIsRefused) {
  placePole(0.008);  // one finger would drag it 8 mm before the other touched
  const GraspClosure c = closeOn(w.workspace(), w.workspace().scene().objectIndex("duster"));
  EXPECT_EQ(c.status, GraspStatus::ClosesOnAir);
  EXPECT_NE(c.detail.find("off the gripper's centre"), std::string::npos) << c.detail;
}

TEST_F(GraspClosureTest, AGraspOnAirFailsAndChangesNothing) {
  placeBook(0, 0.25);  // beyond the finger tips
  const WorldState before = w.workspace().state();
  const GraspClosure c = closeOn(w.workspace(), book);
  EXPECT_EQ(c.status, GraspStatus::ClosesOnAir);
  EXPECT_NE(c.detail.find("closes on air"), std::string::npos) << c.detail;

  const builtins::ActionResult r = builtins::grasp(w, "book_0", 1.0);
  EXPECT_EQ(r.status, builtins::ActionStatus::NoGrip);
  EXPECT_EQ(w.workspace().heldObject(), -1);
  EXPECT_EQ(w.workspace().state().gripper, before.gripper);
  EXPECT_TRUE(w.workspace().objectPose("book_0")->position.isApprox(before.objects.at("book_0").position));
}

TEST_F(GraspClosureTest, AnOpenGripperAlreadyInsideTheBookIsBlocked) {
  placeBook(0.015, kBetweenTheFingers);  // spans -5 .. 35 mm across: through the left finger (22 .. 38 mm)
  const GraspClosure c = closeOn(w.workspace(), book);
  EXPECT_EQ(c.status, GraspStatus::Blocked);
  EXPECT_NE(c.detail.find("inside book_0_geom"), std::string::npos) << c.detail;
}

TEST_F(GraspClosureTest, AHeldBookIsGrippedWhereTheFingersTouchIt) {
  placeBook(0, kBetweenTheFingers);
  WorldState s = w.workspace().state();
  s.gripper = 0.0;  // a state written with the gripper fully closed, as episode starts used to be
  s.held = Grasp{"book_0", Pose3::fromPosition({0, 0, kBetweenTheFingers})};
  ASSERT_EQ(w.workspace().setState(s), StateStatus::Ok);
  EXPECT_LT(gripperContact(w.workspace(), book).separation, -0.015);  // the fingers deep inside the book
  const GraspClosure c = gripHeld(w.workspace());
  ASSERT_TRUE(c.holds()) << c.detail;
  EXPECT_EQ(w.workspace().heldObject(), book);
  EXPECT_NEAR(gripperContact(w.workspace(), book).separation, -kGraspSqueeze, 1e-4);
}

}  // namespace
}  // namespace cbtl::world
