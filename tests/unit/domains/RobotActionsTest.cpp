// The standard-action executor on the home scene: each action's effect on the World, call-shape errors,
// and failures that leave the World unchanged.
#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "robot/actions/CallArguments.h"
#include "robot/actions/ClearanceExceptions.h"
#include "robot/actions/RobotActions.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/actions/SurfaceGeometry.h"
#include "robot/world/Collision.h"
#include "robot/world/GraspClosure.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "tests/unit/domains/HomeTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <optional>
#include <random>

namespace {

using cbtl::actions::RobotActionResult;
using cbtl::actions::RobotActions;
using cbtl::sim::ActionCall;
using cbtl::sim::Value;
using cbtl::world::builtins::ActionStatus;
namespace actions = cbtl::actions;
namespace home = cbtl::domains::home;
namespace world = cbtl::world;

class RobotActionsTest : public ::testing::Test {
 protected:
  RobotActionsTest() : w(cbtl::test::homeScene()), rng(11) {
    world::WorldState s = w.workspace().state();
    s.arm = home::initialArm(*cbtl::test::homeScene());
    EXPECT_EQ(w.workspace().setState(s), world::StateStatus::Ok);
  }

  RobotActionResult run(const std::string& name, std::vector<Value> args) {
    auto r = actions.execute(w, ActionCall{name, std::move(args)});
    EXPECT_TRUE(r.has_value()) << name;
    return r ? *r : RobotActionResult{};
  }

  // Holds book_6 (the book of side table 0) in the carry grasp with the arm at `q`.
  void holdBook(const world::ArmConfig& q) {
    world::WorldState s = w.workspace().state();
    s.arm = q;
    s.held = world::Grasp{"book_6", actions::bookToolInBody().inverse()};
    ASSERT_EQ(w.workspace().setState(s), world::StateStatus::Ok);
  }

  world::World w;
  world::Rng rng{std::mt19937_64::default_seed};  // the stream these tests were written with
  RobotActions actions;
};

TEST_F(RobotActionsTest, OtherNamesAreNotStandard) {
  EXPECT_FALSE(actions.execute(w, ActionCall{"movePot", {}}).has_value());
  EXPECT_TRUE(RobotActions::isStandard("wipe"));
  EXPECT_FALSE(RobotActions::isStandard("movePlate"));  // Feeding's own (domains/feeding/TableSlide.h)
}

TEST_F(RobotActionsTest, MoveBaseMovesTheBase) {
  const RobotActionResult r = run("moveBase", {Value::vec({0.0, -0.55, 0.0})});
  ASSERT_TRUE(r.done()) << r.detail;
  EXPECT_EQ(r.steps, 1);
  EXPECT_NEAR(w.workspace().state().base.y, -0.55, 1e-9);
  EXPECT_EQ(r.simStatus(), cbtl::sim::ActionStatus::Applied);
}

TEST_F(RobotActionsTest, MoveBaseIntoTheWallFailsAndKeepsTheBase) {
  const RobotActionResult r = run("moveBase", {Value::vec({0.0, 1.3, 0.0})});
  EXPECT_FALSE(r.done());
  EXPECT_EQ(r.status, ActionStatus::NoPath);
  EXPECT_EQ(r.steps, 1);
  EXPECT_EQ(r.simStatus(), cbtl::sim::ActionStatus::Ignored);
  EXPECT_NEAR(w.workspace().state().base.y, 0.0, 1e-12);
}

TEST_F(RobotActionsTest, MoveArmAndNamedConfigurations) {
  RobotActionResult r = run("moveArmToNamed", {Value::name("home")});
  ASSERT_TRUE(r.done()) << r.detail;
  EXPECT_EQ(w.workspace().state().arm, world::configs::kHome);
  r = run("moveArm",
          {Value::vec(std::vector<double>(world::configs::kRetract.begin(), world::configs::kRetract.end()))});
  ASSERT_TRUE(r.done()) << r.detail;
  EXPECT_EQ(w.workspace().state().arm, world::configs::kRetract);

  r = run("moveArmToNamed", {Value::name("nowhere")});
  EXPECT_EQ(r.status, ActionStatus::InvalidArgument);
  EXPECT_NE(r.detail.find("nowhere"), std::string::npos);
  EXPECT_NE(r.detail.find("retract"), std::string::npos);           // the message lists the known names
  EXPECT_NE(r.detail.find("homeSceneInitial"), std::string::npos);  // with the scene's own (home.xml)
  EXPECT_EQ(r.detail.find("abovePlate"), std::string::npos);        // but not Feeding's
  EXPECT_EQ(w.workspace().state().arm, world::configs::kRetract);
}

TEST_F(RobotActionsTest, IllFormedCallsAreUnknownActions) {
  const std::vector<ActionCall> bad{
      {"moveBase", {Value::vec({0, 0})}},    // SE2 needs 3 numbers
      {"moveBase", {Value::name("table")}},  // wrong kind
      {"moveArm", {Value::vec({0, 0, 0})}},  // Conf needs 7
      {"grasp", {}},                         // missing argument
      {"grasp", {Value::num(3)}},            // wrong kind
      {"place", {Value::name("table_top"), Value::vec({0, 0, 0})}},
      {"wipe", {Value::vec({0, 0, 0}), Value::name("shelf_layer_1")}},
      {"say", {Value::names({"a"})}},
      {"handOver", {Value::num(1)}},
      {"wait", {Value::name("1")}},
  };
  const world::WorldState before = w.workspace().state();
  for (const ActionCall& call : bad) {
    const auto r = actions.execute(w, call);
    ASSERT_TRUE(r.has_value()) << call.name;
    EXPECT_FALSE(r->wellFormed) << call.name;
    EXPECT_EQ(r->steps, 0) << call.name;
    EXPECT_EQ(r->simStatus(), cbtl::sim::ActionStatus::UnknownAction) << call.name;
    EXPECT_FALSE(r->detail.empty()) << call.name;
  }
  EXPECT_EQ(w.workspace().state().arm, before.arm);
}

TEST_F(RobotActionsTest, NonFiniteValuesFailWithoutThrowing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RobotActionResult r = run("moveBase", {Value::vec({nan, 0, 0})});
  EXPECT_EQ(r.status, ActionStatus::InvalidArgument);
  r = run("moveTool", {Value::vec({0.5, 0, 0.5, 0, 0, 0, 0})});  // zero quaternion
  EXPECT_EQ(r.status, ActionStatus::InvalidArgument);
  EXPECT_TRUE(r.wellFormed);
}

TEST_F(RobotActionsTest, GraspDusterApproachesAttachesAndLifts) {
  ASSERT_TRUE(run("moveBase", {Value::vec({0.0, -0.1, 0.0})}).done());
  const double zBefore = w.workspace().objectPose("duster")->position.z();
  const RobotActionResult r = run("grasp", {Value::name("duster")});
  ASSERT_TRUE(r.done()) << r.detail;
  ASSERT_TRUE(w.workspace().state().held.has_value());
  EXPECT_EQ(w.workspace().state().held->object, "duster");
  // The fingers stop on the 2 cm pole, touching it within the pads' compliance (world/GraspClosure.h).
  EXPECT_GT(w.workspace().state().gripper, 0.0);
  EXPECT_LT(w.workspace().state().gripper, 1.0);
  const world::GripperContact grip = world::gripperContact(w.workspace(), w.workspace().heldObject());
  EXPECT_LE(grip.separation, 0.0);
  EXPECT_GE(grip.separation, -world::kGraspCompliance);
  // Closing further would press the fingers into the pole: refused, nothing changes.
  const double opening = w.workspace().state().gripper;
  const RobotActionResult squeeze = run("closeGripper", {Value::num(1.0)});
  EXPECT_EQ(squeeze.status, ActionStatus::Blocked);
  EXPECT_NE(squeeze.detail.find("duster_pole"), std::string::npos) << squeeze.detail;
  EXPECT_EQ(w.workspace().state().gripper, opening);
  EXPECT_NEAR(w.workspace().objectPose("duster")->position.z(), zBefore + actions::kLift, 2e-3);

  // A second grasp is refused; the duster stays in hand.
  EXPECT_EQ(run("grasp", {Value::name("book_0")}).status, ActionStatus::AlreadyHolding);
  // Releasing drops it back onto the table.
  const RobotActionResult rel = run("release", {});
  ASSERT_TRUE(rel.done()) << rel.detail;
  EXPECT_FALSE(w.workspace().state().held.has_value());
  EXPECT_EQ(actions::supportOf(w, "duster", actions::restingSurfaces(w.workspace().scene())), std::string("table_top"));
}

TEST_F(RobotActionsTest, GraspFailsForUnknownOrDistantBodies) {
  EXPECT_EQ(run("grasp", {Value::name("no_such_body")}).status, ActionStatus::InvalidArgument);
  EXPECT_EQ(run("grasp", {Value::name("book_0")}).status, ActionStatus::OutOfReach);
  EXPECT_FALSE(w.workspace().state().held.has_value());
}

TEST_F(RobotActionsTest, ReleaseNeedsAHeldBodyAndASurfaceBelow) {
  EXPECT_EQ(run("release", {}).status, ActionStatus::NotHolding);
  holdBook(world::configs::kHome);  // the book hangs in the air in front of the robot
  const RobotActionResult r = run("release", {});
  EXPECT_EQ(r.status, ActionStatus::Blocked);
  EXPECT_TRUE(w.workspace().state().held.has_value());
}

TEST_F(RobotActionsTest, PlacePutsTheBookOnTheSideTable) {
  ASSERT_TRUE(run("moveBase", {Value::vec({0.0, -0.55, 0.0})}).done());
  holdBook(world::configs::kHome);
  // Upright, spine along world x as in home.xml, centred on side table 1's top (z = 0): centre at 0.08.
  const world::Pose3 target{Eigen::Vector3d(-0.75, -0.70, 0.08),
                            Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()))};
  // Side table 1 is occupied by book_7 in the scene: move it away first so the target is free.
  w.workspace().setObjectPose("book_7", home::parkedPose(0));
  ASSERT_TRUE(run("moveBase", {Value::vec({0.0, -0.80, 0.0})}).done());
  const RobotActionResult r = run("place", {Value::name("side_table_1_top"), Value::vec(actions::encodePose3(target))});
  ASSERT_TRUE(r.done()) << r.detail;
  EXPECT_FALSE(w.workspace().state().held.has_value());
  const world::Pose3 p = *w.workspace().objectPose("book_6");
  EXPECT_NEAR((p.position - target.position).norm(), 0.0, 1e-6);
  EXPECT_TRUE(actions::restsOn(w, "book_6", p, "side_table_1_top"));
  EXPECT_EQ(w.workspace().state().gripper, 1.0);
}

TEST_F(RobotActionsTest, PlaceRefusesPosesOffTheSurfaceOrOccupied) {
  holdBook(world::configs::kHome);
  const world::WorldState before = w.workspace().state();
  const world::Pose3 floating{Eigen::Vector3d(-0.75, -0.70, 0.3), Eigen::Quaterniond::Identity()};
  EXPECT_EQ(run("place", {Value::name("side_table_1_top"), Value::vec(actions::encodePose3(floating))}).status,
            ActionStatus::InvalidArgument);
  EXPECT_EQ(run("place", {Value::name("no_surface"), Value::vec(actions::encodePose3(floating))}).status,
            ActionStatus::InvalidArgument);
  // Where book_7 stands.
  const world::Pose3 occupied = *w.workspace().objectPose("book_7");
  EXPECT_EQ(run("place", {Value::name("side_table_1_top"), Value::vec(actions::encodePose3(occupied))}).status,
            ActionStatus::Blocked);
  EXPECT_EQ(w.workspace().state().arm, before.arm);
  EXPECT_TRUE(w.workspace().state().held.has_value());
}

TEST_F(RobotActionsTest, HandOverSaysHereYouGo) {
  EXPECT_EQ(run("handOver", {}).status, ActionStatus::NotHolding);
  holdBook(world::configs::kHome);
  const RobotActionResult r = run("handOver", {});
  ASSERT_TRUE(r.done());
  ASSERT_FALSE(w.utterances().empty());
  EXPECT_EQ(w.utterances().back(), "Here you go!");
  EXPECT_TRUE(w.workspace().state().held.has_value());  // the domain decides whether the user takes it
}

// The user may take the object, and the gripper opens to let go: a handover where an open finger would touch
// something is refused (the runtime's dry run then rejects the plan instead of the arm being stuck afterwards).
TEST_F(RobotActionsTest, HandOverWhereTheGripperCannotOpenIsBlocked) {
  holdBook(world::configs::kHome);
  world::Workspace& ws = w.workspace();
  world::WorldState closed = ws.state();
  closed.gripper = 0.0;
  ASSERT_EQ(ws.setState(closed), world::StateStatus::Ok);
  // book_0 stands beside the held book, 1 mm from it, where the right finger goes when the gripper opens: in the
  // end effector's frame the closed finger spans x in [-0.017, -0.001] (inside the held book, which spans
  // [-0.02, 0.02]), the open one [-0.038, -0.022]; book_0 spans [-0.061, -0.021], its long side along y, its
  // 0.10 m side from z = 0.11 to 0.21 (above the gripper's base, which ends at z = 0.095).
  const world::Pose3 ee = ws.bodyPose(ws.scene().bodyId("end_effector_link"));
  const world::Pose3 local{Eigen::Vector3d(-0.041, 0.0, 0.16),
                           Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()))};
  ASSERT_EQ(ws.setObjectPose("book_0", ee * local), world::StateStatus::Ok);
  ASSERT_TRUE(world::checkRobotCollisions(ws).free())
      << world::checkRobotCollisions(ws).first << "/" << world::checkRobotCollisions(ws).second;
  const world::WorldState before = ws.state();
  const RobotActionResult r = run("handOver", {});
  EXPECT_EQ(r.status, ActionStatus::Blocked) << r.detail;
  EXPECT_NE(r.detail.find("could not open"), std::string::npos) << r.detail;
  EXPECT_NE(r.detail.find("book_0"), std::string::npos) << r.detail;
  EXPECT_EQ(ws.state().gripper, before.gripper);  // nothing changed
  EXPECT_EQ(ws.state().arm, before.arm);
  ASSERT_TRUE(ws.state().held.has_value());
  // Moved 3 cm further out, book_0 leaves room for the finger: the handover goes ahead.
  ASSERT_EQ(ws.setObjectPose("book_0", ee * world::Pose3{Eigen::Vector3d(-0.071, 0.0, 0.16), local.orientation}),
            world::StateStatus::Ok);
  const RobotActionResult free = run("handOver", {});
  EXPECT_TRUE(free.done()) << free.detail;
}

TEST_F(RobotActionsTest, SayWaitAndGripper) {
  ASSERT_TRUE(run("say", {Value::name("Done")}).done());
  EXPECT_EQ(w.utterances().back(), "Done");
  EXPECT_EQ(run("waitForUser", {Value::name("button")}).steps, 1);
  EXPECT_EQ(run("wait", {Value::num(3)}).steps, 3);
  EXPECT_EQ(run("wait", {Value::num(0)}).steps, 0);
  EXPECT_EQ(run("wait", {Value::num(-1)}).status, ActionStatus::InvalidArgument);
  EXPECT_EQ(run("wait", {Value::num(1.5)}).status, ActionStatus::InvalidArgument);
  ASSERT_TRUE(run("closeGripper", {Value::num(0.25)}).done());
  EXPECT_DOUBLE_EQ(w.workspace().state().gripper, 0.75);
  EXPECT_EQ(run("closeGripper", {Value::num(2)}).status, ActionStatus::InvalidArgument);
}

TEST_F(RobotActionsTest, StepResultCarriesStatusAndMessage) {
  const RobotActionResult r = run("moveArmToNamed", {Value::name("nowhere")});
  const cbtl::sim::StepResult s = r.toStepResult("moveArmToNamed");
  EXPECT_EQ(s.status, cbtl::sim::ActionStatus::Ignored);
  EXPECT_TRUE(s.consumedStep);
  EXPECT_NE(s.message.find("moveArmToNamed"), std::string::npos);
}

}  // namespace

// The language's built-ins read the duster's standard grasp from home.xml's site duster_tool; it must be the
// grasp the executor uses.
TEST(StandardGrasps, TheSceneSiteIsTheDusterGrasp) {
  cbtl::world::Workspace ws(cbtl::test::homeScene());
  const int site = ws.scene().siteId("duster_tool");
  ASSERT_GE(site, 0);
  const cbtl::world::Pose3 inBody = ws.objectPose("duster")->inverse() * ws.sitePose(site);
  const cbtl::world::Pose3 expected = cbtl::actions::dusterToolInBody();
  EXPECT_LT((inBody.position - expected.position).norm(), 1e-6);
  EXPECT_LT(inBody.orientation.angularDistance(expected.orientation), 1e-6);
}

namespace {

// Every standard grasp of the duster has a collision-free IK solution from the main table's approach base, and
// grasp() takes the duster at the standard grasp the tool is at (not at grasp 0).
TEST_F(RobotActionsTest, EveryDusterGraspIsReachableAndGraspedWhereTheToolIs) {
  ASSERT_TRUE(run("moveBase", {Value::vec({0.0, -0.1, 0.0})}).done());
  ASSERT_EQ(actions::standardGraspCount("duster"), actions::kDusterGraspCount);
  EXPECT_EQ(actions::standardGraspCount("book_0"), 0);
  EXPECT_FALSE(actions::standardGraspTool(w, "duster", actions::kDusterGraspCount).has_value());
  const world::WorldState start = w.workspace().state();
  for (int k = 0; k < actions::kDusterGraspCount; ++k) {
    ASSERT_EQ(w.workspace().setState(start), world::StateStatus::Ok);
    const auto tool = actions::standardGraspTool(w, "duster", k);
    ASSERT_TRUE(tool.has_value());
    world::Rng ikRng(5);
    const world::IkResult ik = world::solveIk(w.workspace(), *tool, start.arm, ikRng);
    ASSERT_TRUE(ik.solved()) << "grasp " << k << ": " << world::toString(ik.status) << " " << ik.collision.first << "/"
                             << ik.collision.second;
    ASSERT_EQ(w.workspace().setState(start), world::StateStatus::Ok);
    ASSERT_TRUE(run("moveArm", {Value::vec(std::vector<double>(ik.q.begin(), ik.q.end()))}).done()) << k;
    const RobotActionResult r = run("grasp", {Value::name("duster")});
    ASSERT_TRUE(r.done()) << "grasp " << k << ": " << r.detail;
    const world::Pose3 held = w.workspace().state().held->toolToObject.inverse();
    const world::Pose3 expected = actions::dusterToolInBody(k);
    EXPECT_LT((held.position - expected.position).norm(), 2e-3) << "grasp " << k;
  }
}

}  // namespace

// A book stowed 1.8 cm from the shelf's right support (where Books seed 5 once put one): the open gripper fits
// at the pre-grasp and at the grasp, but the joint-space segment between them bows the left finger into the
// support. moveTool follows the tool's line instead, and every configuration on the way is free.
TEST_F(RobotActionsTest, MoveToolFollowsTheToolLineWhereTheJointSegmentTouches) {
  world::Workspace& ws = w.workspace();
  world::WorldState s = ws.state();
  for (auto& [name, pose] : s.objects) pose.position += Eigen::Vector3d(20, 20, 0);  // park everything
  const world::Pose3 book{Eigen::Vector3d(0.3621, 0.6546, 0.13), Eigen::Quaterniond::Identity()};
  s.objects["book_4"] = book;
  s.base = {0, 0, 0};
  s.arm = world::configs::kRetract;
  s.gripper = 1.0;
  s.held.reset();
  ASSERT_EQ(ws.setState(s), world::StateStatus::Ok);
  // The side grasp of books.cbtl (tool z along the book's +y, 3 cm before its centre) and its pre-grasp 8 cm behind.
  const Eigen::Quaterniond inBook(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d along = inBook * Eigen::Vector3d::UnitZ();
  const world::Pose3 graspTool = book * world::Pose3{-0.03 * along, inBook};
  const world::Pose3 preGraspTool = book * world::Pose3{-0.11 * along, inBook};
  world::Rng seed(3);
  const world::IkResult pre = world::solveIk(ws, preGraspTool, world::configs::kRetract, seed);
  ASSERT_TRUE(pre.solved());
  ws.setArm(pre.q);
  world::Rng ikRng(5);
  const world::IkResult in = world::solveIk(ws, graspTool, pre.q, ikRng);
  ASSERT_TRUE(in.solved());
  ws.setArm(pre.q);
  ASSERT_FALSE(world::armSegmentFree(ws, pre.q, in.q)) << "the scenario needs a joint segment that touches";
  ws.setArm(pre.q);

  const RobotActionResult r = run("moveTool", {Value::vec(actions::encodePose3(graspTool))});
  ASSERT_TRUE(r.done()) << r.detail;
  EXPECT_LT((ws.toolPose().position - graspTool.position).norm(), 2e-3);
  EXPECT_LT(world::rotationDistance(ws.toolPose().orientation, graspTool.orientation), 0.02);
  ASSERT_GE(r.armPath.size(), 3u);  // followed the line in steps
  for (std::size_t k = 1; k < r.armPath.size(); ++k)
    EXPECT_TRUE(world::armSegmentFree(ws, r.armPath[k - 1], r.armPath[k])) << "step " << k;
  EXPECT_EQ(run("grasp", {Value::name("book_4")}).status, ActionStatus::Done);
}

namespace {

// A skill's `allow` reaches the executor as names: a body covers its whole subtree, a geom itself.
TEST(ClearanceExceptions, NamesResolveToBodiesWithTheirSubtreesOrToGeoms) {
  const auto& scene = *cbtl::test::homeScene();
  std::vector<world::ContactAllowance> out;
  std::string error;
  ASSERT_TRUE(actions::resolveClearanceExceptions(
      scene, {{"held", {"mobile_base", "user_forearm_r"}, -0.002, "b.cbtl:9:5"}}, out, error))
      << error;
  std::size_t bodies = 0, geoms = 0;
  for (const auto& a : out) {
    EXPECT_EQ(a.part, world::ContactAllowance::Part::HeldObject);
    EXPECT_DOUBLE_EQ(a.separation, -0.002);
    if (a.geom >= 0) {
      ++geoms;
      EXPECT_EQ(scene.geomName(a.geom), "user_forearm_r");
    } else {
      ++bodies;
    }
  }
  EXPECT_EQ(geoms, 1u);
  // The mobile base carries the whole arm: its subtree reaches the gripper.
  EXPECT_GT(bodies, 8u);
  const int ee = scene.bodyId("end_effector_link");
  EXPECT_TRUE(std::any_of(out.begin(), out.end(), [&](const auto& a) { return a.body == ee; }));

  out.clear();
  EXPECT_FALSE(actions::resolveClearanceExceptions(scene, {{"held", {"nobody"}, 0.01, "b.cbtl:9:5"}}, out, error));
  EXPECT_EQ(error, "allow at b.cbtl:9:5: the scene has no body or geom 'nobody'");
  EXPECT_FALSE(actions::resolveClearanceExceptions(scene, {{"elbow", {"user"}, 0.01, ""}}, out, error));
  EXPECT_NE(error.find("'elbow' is not a part of the robot"), std::string::npos) << error;
}

// The executor refuses a call whose exception names nothing in the scene, and changes nothing.
TEST_F(RobotActionsTest, AnExceptionNamingNoBodyFailsTheAction) {
  const world::WorldState before = w.workspace().state();
  ActionCall call{"moveArmToNamed", {Value::name("retract")}, {{"held", {"nobody"}, 0.01, "b.cbtl:9:5"}}};
  const auto r = actions.execute(w, call);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->status, ActionStatus::InvalidArgument);
  EXPECT_NE(r->detail.find("no body or geom 'nobody'"), std::string::npos) << r->detail;
  EXPECT_EQ(w.workspace().state().arm, before.arm);
}

}  // namespace
