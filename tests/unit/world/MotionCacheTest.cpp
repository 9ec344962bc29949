// The motion cache changes speed, never results: a cached answer equals a fresh plan of the same query, the
// budget is not part of the key but decides whether an entry answers, every input of a plan is in the key, and
// eviction is first in, first out.
#include "robot/world/CartesianPath.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionQuery.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <memory>

namespace cbtl::world {
namespace {

// A valid start whose straight segment to `goal` is blocked, so planning must run RRTConnect.
ArmConfig blockedStart(Workspace& ws, const ArmConfig& goal, std::uint64_t seed) {
  Rng rng(seed);
  ArmConfig a;
  do {
    do a = randomConfig(ws.scene(), rng);
    while (!checkArm(ws, a).free());
  } while (armSegmentFree(ws, a, goal));
  return a;
}

std::unique_ptr<Workspace> startedAt(const ArmConfig& start) {
  auto ws = std::make_unique<Workspace>(test::feedingScene());
  WorldState st;
  st.arm = start;
  EXPECT_EQ(ws->setState(st), StateStatus::Ok);
  return ws;
}

TEST(WorldMotionCache, ACachedAnswerEqualsAFreshPlanOfTheSameQuery) {
  const ArmConfig goal = configs::kRetract;
  Workspace probe(test::feedingScene());
  const ArmConfig start = blockedStart(probe, goal, 21);
  auto ws = startedAt(start);
  PlanOptions o;
  const MotionQuery q = armQuery(*ws, goal, o);

  const MotionCacheStats before = ws->scene().motionCache().stats();
  const ArmPlan first = planArmCached(*ws, goal, o);
  ASSERT_TRUE(first.solved());
  EXPECT_GT(first.iterations, 0);

  auto again = startedAt(start);
  const ArmPlan cached = planArmCached(*again, goal, o);
  const MotionCacheStats after = ws->scene().motionCache().stats();
  EXPECT_GE(after.hits, before.hits + 1);
  EXPECT_EQ(cached.status, first.status);
  EXPECT_EQ(cached.path, first.path);
  EXPECT_EQ(cached.iterations, first.iterations);

  // The planner's stream is seeded from the query, so planning afresh with that seed gives the same path.
  auto fresh = startedAt(start);
  Rng rng(q.fingerprint);
  const ArmPlan direct = planArm(*fresh, start, goal, rng, o);
  EXPECT_EQ(direct.status, first.status);
  EXPECT_EQ(direct.path, first.path);
  EXPECT_EQ(direct.iterations, first.iterations);
}

// A Cartesian tool line is cached too (kind Line): asked again from the same state it is a lookup with the same
// waypoints; a line with other step limits is a different query.
TEST(WorldMotionCache, ACachedToolLineEqualsTheFreshOne) {
  auto ws = startedAt(configs::kHome);
  const Pose3 target = ws->toolPose() * Pose3::fromPosition({0.0, 0.031, -0.047});
  const IkOptions ik;
  CartesianPathOptions line;
  line.maxStep = 0.004;
  MotionCache& cache = ws->scene().motionCache();
  const MotionCacheStats before = cache.stats();
  const auto first = cartesianToolPath(*ws, target, ik, line);
  ASSERT_TRUE(first.has_value());
  EXPECT_GT(first->size(), 5u);
  EXPECT_EQ(cache.stats().stored, before.stored + 1);
  auto again = startedAt(configs::kHome);
  const auto cached = cartesianToolPath(*again, target, ik, line);
  EXPECT_EQ(cache.stats().hits, before.hits + 1);
  ASSERT_TRUE(cached.has_value());
  EXPECT_EQ(*cached, *first);
  line.maxStep = 0.005;
  const auto coarser = cartesianToolPath(*again, target, ik, line);
  EXPECT_EQ(cache.stats().hits, before.hits + 1);
  ASSERT_TRUE(coarser.has_value());
  EXPECT_LT(coarser->size(), first->size());
}

TEST(WorldMotionCache, TheBudgetDecidesWhetherAnEntryAnswers) {
  MotionAnswer solved;
  solved.status = PlanStatus::Solved;
  solved.budget = 1000;
  solved.iterations = 40;
  EXPECT_TRUE(solved.answers(40));
  EXPECT_TRUE(solved.answers(100000));
  EXPECT_FALSE(solved.answers(39));  // a smaller budget would have run out first

  MotionAnswer exhausted;
  exhausted.status = PlanStatus::BudgetExhausted;
  exhausted.budget = 1000;
  EXPECT_TRUE(exhausted.answers(0));
  EXPECT_TRUE(exhausted.answers(1000));
  EXPECT_FALSE(exhausted.answers(1001));  // a larger budget may still find a path

  MotionAnswer invalid;
  invalid.status = PlanStatus::InvalidGoal;
  invalid.budget = 0;
  EXPECT_TRUE(invalid.answers(1 << 20));  // no budget makes an invalid goal valid
}

TEST(WorldMotionCache, AFailureWithASmallBudgetIsPlannedAgainWithALargerOne) {
  const ArmConfig goal = test::feedingConf("abovePlate");
  Workspace probe(test::feedingScene());
  const ArmConfig start = blockedStart(probe, goal, 33);
  auto ws = startedAt(start);
  PlanOptions tiny;
  tiny.maxIterations = 0;
  const ArmPlan straight = planArmCached(*ws, goal, tiny);
  EXPECT_EQ(straight.status, PlanStatus::BudgetExhausted);

  PlanOptions full;  // same key: only the budget differs
  ASSERT_EQ(armQuery(*ws, goal, tiny).fingerprint, armQuery(*ws, goal, full).fingerprint);
  auto again = startedAt(start);
  const ArmPlan planned = planArmCached(*again, goal, full);
  ASSERT_TRUE(planned.solved());

  auto fresh = startedAt(start);
  Rng rng(armQuery(*fresh, goal, full).fingerprint);
  EXPECT_EQ(planArm(*fresh, start, goal, rng, full).path, planned.path);
}

TEST(WorldMotionCache, EveryInputOfAPlanIsInTheKey) {
  Workspace ws(test::homeScene());
  WorldState st;
  st.arm = configs::kRetract;
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  PlanOptions o;
  const ArmConfig goal = configs::kHome;
  const std::uint64_t base = armQuery(ws, goal, o).fingerprint;
  EXPECT_EQ(armQuery(ws, goal, o).fingerprint, base);

  ArmConfig otherGoal = goal;
  otherGoal[0] += 1e-9;
  EXPECT_NE(armQuery(ws, otherGoal, o).fingerprint, base);
  EXPECT_NE(baseQuery(ws, {0, 0, 0}, o).fingerprint, base);

  PlanOptions allowing = o;
  ContactAllowance touch;
  touch.geom = 0;
  touch.separation = -0.001;
  allowing.collision.allowances.push_back(touch);
  EXPECT_NE(armQuery(ws, goal, allowing).fingerprint, base);

  ASSERT_FALSE(ws.scene().objects().empty());
  const std::string name = ws.scene().objects().front().name;
  const auto at = ws.objectPose(name);
  ASSERT_TRUE(at.has_value());
  ASSERT_EQ(ws.setObjectPose(name, *at), StateStatus::Ok);
  const std::uint64_t placed = armQuery(ws, goal, o).fingerprint;
  Pose3 p = *at;
  p.position.x() += 0.01;
  ASSERT_EQ(ws.setObjectPose(name, p), StateStatus::Ok);
  EXPECT_NE(armQuery(ws, goal, o).fingerprint, placed) << "moving " << name << " must change the key";

  WorldState closed = ws.state();
  closed.gripper = 0.0;
  ws.setState(closed);
  EXPECT_NE(armQuery(ws, goal, o).fingerprint, base);
}

TEST(WorldMotionCache, TheTableInUseIsInTheKey) {
  // The feeding scene's tables are fixtures: a path planned around one table never answers for the other.
  Workspace ws(test::feedingScene());
  PlanOptions o;
  const std::uint64_t rectangular = armQuery(ws, configs::kHome, o).fingerprint;
  const Pose3 inUse = ws.state().fixtures.at("table"), parked = ws.state().fixtures.at("table_round");
  ASSERT_EQ(ws.setFixturePose("table", parked), StateStatus::Ok);
  ASSERT_EQ(ws.setFixturePose("table_round", inUse), StateStatus::Ok);
  EXPECT_NE(armQuery(ws, configs::kHome, o).fingerprint, rectangular);
}

TEST(WorldMotionCache, EntriesBeyondTheCapacityEvictTheOldest) {
  MotionCache cache(2);
  auto query = [](double v) {
    MotionQuery q;
    q.key = {v};
    q.fingerprint = fingerprintOf(q.key);
    return q;
  };
  MotionAnswer a;
  a.status = PlanStatus::InvalidGoal;
  for (double v : {1.0, 2.0, 3.0}) cache.store(query(v), a);
  EXPECT_FALSE(cache.find(query(1.0), 0).has_value());
  EXPECT_TRUE(cache.find(query(2.0), 0).has_value());
  EXPECT_TRUE(cache.find(query(3.0), 0).has_value());
  const MotionCacheStats s = cache.stats();
  EXPECT_EQ(s.stored, 3u);
  EXPECT_EQ(s.evicted, 1u);
  EXPECT_EQ(s.hits, 2u);
  EXPECT_EQ(s.misses, 1u);

  // A query whose fingerprint collides with a stored one but whose key differs is a miss, never a wrong answer.
  MotionQuery impostor = query(2.0);
  impostor.key = {99.0};
  EXPECT_FALSE(cache.find(impostor, 0).has_value());
}

}  // namespace
}  // namespace cbtl::world
