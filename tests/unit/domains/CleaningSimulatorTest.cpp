// The Cleaning simulator: episode starts, observations, requested tasks, the user's reactions to wipes,
// failures, and the evaluation twin.
#include "domains/cleaning/CleaningSimulator.h"

#include "robot/actions/CallArguments.h"
#include "tests/unit/domains/HomeTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace {

using cbtl::domains::cleaning::CleaningSimulator;
using cbtl::domains::cleaning::CleaningUser;
using cbtl::sim::ActionCall;
using cbtl::sim::ActionStatus;
using cbtl::sim::StepResult;
using cbtl::sim::Value;
namespace actions = cbtl::actions;
namespace home = cbtl::domains::home;
namespace world = cbtl::world;

// As cleaning.cbtl's wipeSurface calls it: inside `allow held touch surfaceGeom[surface] 5 mm { ... }`.
ActionCall wipe(const std::string& surface, const world::Pose2& base) {
  ActionCall call{"wipe", {Value::name(surface), Value::vec({base.x, base.y, base.yaw})}};
  call.exceptions.push_back({"held", {surface}, -0.005, "cleaning.cbtl:137:5"});
  return call;
}

TEST(CleaningSimulator, ResetIsDeterministic) {
  CleaningSimulator a(cbtl::test::homeFacts(), {}, 42), b(cbtl::test::homeFacts(), {}, 7);
  b.reset(42);
  const auto oa = a.observe(), ob = b.observe();
  EXPECT_EQ(oa.at("clearSurfaces").members, ob.at("clearSurfaces").members);
  EXPECT_EQ(oa.at("heldBody").text, ob.at("heldBody").text);
  EXPECT_EQ(oa.at("basePose").vector, ob.at("basePose").vector);
  for (const auto& [name, pose] : a.worldState()->objects) {
    EXPECT_EQ(pose.position, b.worldState()->objects.at(name).position) << name;
  }
}

TEST(CleaningSimulator, ObservationsHaveTheDeclaredNamesAndKinds) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 1);
  const auto o = sim.observe();
  ASSERT_EQ(o.size(), 3u);
  EXPECT_EQ(o.at("clearSurfaces").kind, Value::Kind::Names);
  EXPECT_EQ(o.at("heldBody").kind, Value::Kind::Name);
  ASSERT_EQ(o.at("basePose").kind, Value::Kind::Vector);
  EXPECT_EQ(o.at("basePose").vector, (std::vector<double>{0, 0, 0}));
  const std::set<std::string> members{"mainTable",  "shelfBottom", "shelfMiddle", "shelfTop",
                                      "sideTable0", "sideTable1",  "sideTable2"};
  for (const std::string& m : o.at("clearSurfaces").members) EXPECT_EQ(members.count(m), 1u) << m;
}

TEST(CleaningSimulator, EpisodesCoverOneSurfaceAndEveryHeldCaseWithValidStarts) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 0);
  std::set<std::string> tasks;
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    sim.reset(seed);
    const auto o = sim.observe();
    const std::string held = o.at("heldBody").text;
    const std::string task = sim.requestedTask();
    if (held.empty())
      EXPECT_EQ(task, "cleanSurface");
    else if (held == "duster")
      EXPECT_EQ(task, "cleanWithDusterInHand");
    else
      EXPECT_EQ(task, "stowThenClean") << held;
    tasks.insert(task);
    EXPECT_EQ(o.at("clearSurfaces").members.size(), 6u) << "seed " << seed;
    EXPECT_TRUE(world::checkRobotCollisions(sim.world().workspace()).free()) << "seed " << seed;
  }
  EXPECT_EQ(tasks.size(), 3u);
}

TEST(CleaningSimulator, ABookOnASurfaceMakesItUnclear) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 3);
  world::Rng rng(1);
  ASSERT_TRUE(cbtl::test::holdAt(sim.world(), "duster", {0, 0, 0}));
  EXPECT_EQ(sim.clearSurfaces().size(), 7u);  // the duster in hand, every book parked
  const auto pose = world::builtins::samplePlacement(sim.world(), "book_4", "side_table_2_top", 0.0, rng);
  ASSERT_TRUE(pose.has_value());
  sim.world().workspace().setObjectPose("book_4", *pose);
  const auto clear = sim.clearSurfaces();
  EXPECT_EQ(clear.size(), 6u);
  EXPECT_EQ(std::find(clear.begin(), clear.end(), "sideTable2"), clear.end());
}

TEST(CleaningSimulator, AWipeOfAWelcomeSurfaceIsThanked) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 5);
  world::Rng rng(2);
  ASSERT_TRUE(cbtl::test::readyToWipe(sim.world(), "shelf_layer_1", {0, 0, 0}, rng));
  const StepResult r = sim.act(wipe("shelf_layer_1", {0, 0, 0}));
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_TRUE(r.consumedStep);
  EXPECT_FALSE(r.taskDone) << "the task ends when the robot says Done";
  ASSERT_TRUE(r.hasSatisfaction);
  EXPECT_EQ(r.satisfaction, 1.0);
  ASSERT_EQ(r.feedback.size(), 1u);
  EXPECT_EQ(r.feedback[0].name, "cleaningReaction");
  ASSERT_EQ(r.feedback[0].args.size(), 2u);
  EXPECT_EQ(r.feedback[0].args[0].text, "shelfMiddle");
  EXPECT_EQ(r.feedback[0].args[1].number, 1.0);
  const StepResult done = sim.act(ActionCall{"say", {Value::name("Done")}});
  ASSERT_EQ(done.status, ActionStatus::Applied) << done.message;
  EXPECT_TRUE(done.taskDone);
  EXPECT_FALSE(done.hasSatisfaction);
  EXPECT_TRUE(done.feedback.empty());
}

TEST(CleaningSimulator, SayingDoneWithoutAWipeEndsNoTask) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 5);
  const StepResult r = sim.act(ActionCall{"say", {Value::name("Done")}});
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_FALSE(r.taskDone);
}

TEST(CleaningSimulator, ACaregiverResetsARobotThatStaysIdle) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 5);
  world::Rng rng(2);
  ASSERT_TRUE(cbtl::test::readyToWipe(sim.world(), "shelf_layer_1", {0.3, 0.1, 0.5}, rng));
  for (int i = 1; i < home::kCaregiverPatience; ++i) EXPECT_FALSE(sim.idle().caregiverReset) << i;
  const StepResult r = sim.idle();
  EXPECT_TRUE(r.caregiverReset);
  const world::WorldState& s = *sim.worldState();
  EXPECT_EQ(s.base.x, 0.0);
  EXPECT_EQ(s.base.yaw, 0.0);
  ASSERT_TRUE(s.held.has_value());  // the duster stays in the hand, carried
  EXPECT_EQ(s.held->object, "duster");
  EXPECT_EQ(s.arm, world::configs::kHome);
  EXPECT_FALSE(sim.idle().caregiverReset) << "the count starts again";
}

TEST(CleaningSimulator, AWipeOfAnUnwelcomeSurfaceIsAdmonished) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 5);
  world::Rng rng(2);
  ASSERT_TRUE(cbtl::test::readyToWipe(sim.world(), "shelf_layer_2", {0, 0, 0}, rng));
  const StepResult r = sim.act(wipe("shelf_layer_2", {0, 0, 0}));
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_FALSE(r.taskDone);
  EXPECT_EQ(r.satisfaction, -1.0);
  ASSERT_EQ(r.feedback.size(), 1u);
  EXPECT_EQ(r.feedback[0].args[0].text, "shelfTop");
  EXPECT_EQ(r.feedback[0].args[1].number, 0.0);
}

TEST(CleaningSimulator, FetchingTheDusterThenWipingFollowsTheSkills) {
  // cleanSurface's plan shape: fetchDuster (base to the table, grasp, home) then wipeSurface.
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 0);
  const world::World fresh(cbtl::test::homeScene());  // home.xml's poses: the duster on the main table
  const world::WorldState s = home::emptyRoom(*cbtl::test::homeScene(), fresh.workspace().state().objects);
  ASSERT_EQ(sim.world().workspace().setState(s), world::StateStatus::Ok);
  EXPECT_EQ(sim.requestedTask(), "cleanSurface");
  for (const ActionCall& call :
       {ActionCall{"moveBase", {Value::vec({0, -0.1, 0})}}, ActionCall{"grasp", {Value::name("duster")}},
        ActionCall{"moveArmToNamed", {Value::name("home")}}}) {
    const StepResult r = sim.act(call);
    ASSERT_EQ(r.status, ActionStatus::Applied) << call.name << ": " << r.message;
    EXPECT_FALSE(r.taskDone);
  }
  EXPECT_EQ(sim.requestedTask(), "cleanWithDusterInHand");
  ASSERT_EQ(sim.act(ActionCall{"moveBase", {Value::vec({0, -0.55, 0})}}).status, ActionStatus::Applied);
  world::Rng rng(4);
  const auto tool = actions::preWipeToolPose(sim.world(), "side_table_0_top", "duster",
                                             sim.worldState()->held->toolToObject, {0, -0.55, 0});
  ASSERT_TRUE(tool.has_value());
  const auto q = world::builtins::sampleIk(sim.world(), *tool, rng);
  ASSERT_TRUE(q.has_value());
  ASSERT_EQ(sim.act(ActionCall{"moveArm", {Value::vec(std::vector<double>(q->begin(), q->end()))}}).status,
            ActionStatus::Applied);
  const StepResult r = sim.act(wipe("side_table_0_top", {0, -0.55, 0}));
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_EQ(r.satisfaction, 1.0);
  EXPECT_EQ(r.feedback.at(0).args.at(0).text, "sideTable0");
}

TEST(CleaningSimulator, AFailedActionEndsTheTaskWithoutAJudgement) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 1);
  const world::Pose2 before = sim.worldState()->base;
  const StepResult r = sim.act(ActionCall{"moveBase", {Value::vec({0, 1.3, 0})}});  // into the back wall
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  EXPECT_TRUE(r.consumedStep);
  EXPECT_TRUE(r.taskDone);
  EXPECT_FALSE(r.hasSatisfaction);
  EXPECT_TRUE(r.feedback.empty());
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(sim.worldState()->base.y, before.y);
}

TEST(CleaningSimulator, UnknownAndIllFormedCallsAreRejected) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 1);
  StepResult r = sim.act(ActionCall{"movePot", {}});
  EXPECT_EQ(r.status, ActionStatus::UnknownAction);
  EXPECT_FALSE(r.consumedStep);
  r = sim.act(ActionCall{"wipe", {Value::name("table_top")}});
  EXPECT_EQ(r.status, ActionStatus::UnknownAction);
  EXPECT_FALSE(r.consumedStep);
  EXPECT_FALSE(r.taskDone);
  r = sim.idle();
  EXPECT_TRUE(r.consumedStep);
}

TEST(CleaningSimulator, EvaluationTwinSharesTheUserNotTheWorld) {
  CleaningSimulator sim(cbtl::test::homeFacts(), {}, 9, CleaningUser({"shelfTop"}));
  auto twin = sim.makeEvaluationTwin();
  auto* t = dynamic_cast<CleaningSimulator*>(twin.get());
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(&t->user(), &sim.user());
  world::Rng rng(3);
  ASSERT_TRUE(cbtl::test::readyToWipe(t->world(), "shelf_layer_2", {0, 0, 0}, rng));
  const world::ArmConfig trainArm = sim.worldState()->arm;
  const StepResult r = t->act(wipe("shelf_layer_2", {0, 0, 0}));
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_EQ(r.satisfaction, 1.0);  // this user welcomes the top layer
  EXPECT_EQ(sim.worldState()->arm, trainArm);
}

}  // namespace
