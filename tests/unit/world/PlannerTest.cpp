// Motion planning: solved paths are re-checked densely with exact state checks (an independent look at what the
// certificates proved); statuses for invalid endpoints; the SE(2) base planner; determinism.
#include "robot/world/InverseKinematics.h"
#include "robot/world/JointPath.h"
#include "robot/world/MotionPlanner.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <utility>

namespace cbtl::world {
namespace {

// The path with extra waypoints so that consecutive waypoints are at most `spacing` apart (L∞).
std::vector<Waypoint> densify(const JointSpace& space, const std::vector<Waypoint>& path, double spacing) {
  if (path.empty()) return {};
  std::vector<Waypoint> out{path.front()};
  for (std::size_t i = 1; i < path.size(); ++i) {
    const long n = std::max(1L, static_cast<long>(std::ceil(linfDistance(space, path[i - 1], path[i]) / spacing)));
    for (long k = 1; k < n; ++k)
      out.push_back(interpolate(space, path[i - 1], path[i], static_cast<double>(k) / static_cast<double>(n)));
    out.push_back(path[i]);
  }
  return out;
}

// Every interpolated state of the path at `spacing` (rad, L∞) is collision-free and within limits.
void expectPathFree(Workspace& ws, const std::vector<ArmConfig>& path, double spacing) {
  JointSpace space;
  for (int i = 0; i < kArmDof; ++i) space.circular.push_back(ws.scene().armContinuous(i));
  std::vector<Waypoint> wps;
  for (const ArmConfig& q : path) wps.emplace_back(q.begin(), q.end());
  std::vector<ArmConfig> dense;
  for (const Waypoint& w : densify(space, wps, spacing)) {
    ArmConfig q{};
    std::copy(w.begin(), w.end(), q.begin());
    dense.push_back(q);
  }
  for (std::size_t i = 0; i < dense.size(); ++i) {
    ASSERT_TRUE(ws.scene().withinLimits(dense[i])) << "waypoint " << i;
    const auto r = checkArm(ws, dense[i]);
    ASSERT_TRUE(r.free()) << "waypoint " << i << ": " << r.first << " / " << r.second;
  }
}

// A valid pair whose straight segment is blocked, so that planning must run RRTConnect.
std::pair<ArmConfig, ArmConfig> blockedPair(Workspace& ws, Rng& rng) {
  ArmConfig a, b;
  do {
    do a = randomConfig(ws.scene(), rng);
    while (!checkArm(ws, a).free());
    do b = randomConfig(ws.scene(), rng);
    while (!checkArm(ws, b).free());
  } while (armSegmentFree(ws, a, b));
  return {a, b};
}

TEST(WorldPlanner, RetractToAbovePlate) {
  Workspace ws(test::feedingScene());
  Rng rng(5);
  const ArmPlan plan = planArm(ws, configs::kRetract, test::feedingConf("abovePlate"), rng);
  ASSERT_EQ(plan.status, PlanStatus::Solved);
  ASSERT_GE(plan.path.size(), 2U);
  EXPECT_EQ(plan.path.front(), configs::kRetract);
  EXPECT_EQ(plan.path.back(), test::feedingConf("abovePlate"));
  expectPathFree(ws, plan.path, 0.0025);
}

TEST(WorldPlanner, RandomValidQueriesGiveFreePaths) {
  Workspace ws(test::feedingScene());
  Rng rng(11);
  int solved = 0;
  for (int i = 0; i < 8; ++i) {
    ArmConfig a, b;
    do a = randomConfig(ws.scene(), rng);
    while (!checkArm(ws, a).free());
    do b = randomConfig(ws.scene(), rng);
    while (!checkArm(ws, b).free());
    const ArmPlan plan = planArm(ws, a, b, rng);
    if (!plan.solved()) continue;
    ++solved;
    expectPathFree(ws, plan.path, 0.0025);
  }
  EXPECT_GE(solved, 7);
}

TEST(WorldPlanner, InvalidEndpointsAreReported) {
  Workspace ws(test::feedingScene());
  Rng rng(1);
  const ArmConfig inTable{-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004};
  EXPECT_EQ(planArm(ws, inTable, configs::kRetract, rng).status, PlanStatus::InvalidStart);
  EXPECT_EQ(planArm(ws, configs::kRetract, inTable, rng).status, PlanStatus::InvalidGoal);
  const ArmConfig outOfLimits{0, 2.5, 0, 0, 0, 0, 0};
  EXPECT_EQ(planArm(ws, configs::kRetract, outOfLimits, rng).status, PlanStatus::InvalidGoal);
}

TEST(WorldPlanner, TinyBudgetIsExhausted) {
  Workspace ws(test::feedingScene());
  Rng rng(2);
  PlanOptions o;
  o.maxIterations = 0;
  const auto [a, b] = blockedPair(ws, rng);
  const ArmPlan plan = planArm(ws, a, b, rng, o);
  EXPECT_EQ(plan.status, PlanStatus::BudgetExhausted);
  EXPECT_TRUE(plan.path.empty());
}

TEST(WorldPlanner, SameSeedSamePath) {
  // The plan depends only on the Rng, not on what the process planned before (OMPL creates generators of
  // its own, seeded from a process-wide sequence, and the planner never draws from them).
  Workspace ws(test::feedingScene());
  Rng pairs(4);
  const auto [start, goal] = blockedPair(ws, pairs);
  Rng a(77), b(77), other(78);
  const ArmPlan p1 = planArm(ws, start, goal, a);
  ASSERT_TRUE(p1.solved());
  EXPECT_GT(p1.iterations, 0);
  const ArmPlan between = planArm(ws, start, goal, other);
  const ArmPlan p2 = planArm(ws, start, goal, b);
  EXPECT_EQ(p1.path, p2.path);
  EXPECT_EQ(p1.iterations, p2.iterations);
  EXPECT_EQ(a.next(), b.next());  // both consumed the same number of words
  ASSERT_TRUE(between.solved());
  EXPECT_NE(between.path, p1.path);  // the seed matters
}

TEST(WorldPlanner, BaseAroundTheTableInTheHomeScene) {
  Workspace ws(test::homeScene());
  WorldState st;
  st.arm = configs::kRetract;
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  Rng rng(3);
  const BasePlan plan = planBase(ws, {0.0, -0.55, 0.0}, rng);
  ASSERT_EQ(plan.status, PlanStatus::Solved);
  ASSERT_GE(plan.path.size(), 2U);
  // Re-check the base path at 2.5 mm / 2.5 mrad.
  JointSpace se2{{false, false, true}};
  std::vector<Waypoint> wps;
  for (const auto& p : plan.path) wps.push_back({p.x, p.y, p.yaw});
  for (const auto& w : densify(se2, wps, 0.0025)) {
    ws.setBase({w[0], w[1], w[2]});
    ASSERT_TRUE(checkRobotCollisions(ws).free());
  }
}

TEST(WorldPlanner, BasePlanningNeedsAMobileBase) {
  Workspace ws(test::feedingScene());
  Rng rng(3);
  EXPECT_EQ(planBase(ws, {0.1, 0.0, 0.0}, rng).status, PlanStatus::NoMobileBase);
}

}  // namespace
}  // namespace cbtl::world
