// Inverse kinematics: round trips from forward kinematics, and honest failure for unreachable targets.
#include "robot/world/InverseKinematics.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

TEST(WorldIk, RoundTripsOnRandomReachableTargets) {
  Workspace ws(test::feedingScene());
  Rng rng(42);
  int solved = 0, trials = 0;
  while (trials < 100) {
    const ArmConfig q = randomConfig(ws.scene(), rng);
    if (!checkArm(ws, q).free()) continue;
    ++trials;
    const Pose3 target = ws.forwardKinematics(q);
    const IkResult r = solveIk(ws, target, configs::kRetract, rng);
    if (!r.solved()) continue;
    ++solved;
    const Pose3 got = ws.forwardKinematics(r.q);
    EXPECT_LT((got.position - target.position).norm(), 1e-3);
    EXPECT_LT(rotationDistance(got.orientation, target.orientation), 1e-2);
    EXPECT_TRUE(ws.scene().withinLimits(r.q));
    EXPECT_TRUE(checkArm(ws, r.q).free());
  }
  EXPECT_GE(solved, 98);
}

TEST(WorldIk, SeedNearSolutionConvergesQuickly) {
  Workspace ws(test::feedingScene());
  Rng rng(1);
  const Pose3 target = ws.forwardKinematics(test::feedingConf("abovePlate")) * Pose3::fromPosition({0.02, -0.03, 0.01});
  const IkResult r = solveIk(ws, target, test::feedingConf("abovePlate"), rng);
  ASSERT_TRUE(r.solved()) << toString(r.status);
  EXPECT_EQ(r.attempts, 1);
  EXPECT_LT(r.iterations, 60);
}

TEST(WorldIk, UnreachableTargetIsNotConverged) {
  Workspace ws(test::feedingScene());
  Rng rng(7);
  IkOptions o;
  o.maxAttempts = 3;
  const IkResult r = solveIk(ws, Pose3::fromPosition({2.0, 0.0, 0.5}), configs::kRetract, rng, o);
  EXPECT_EQ(r.status, IkStatus::NotConverged);
  EXPECT_EQ(r.attempts, 3);
}

TEST(WorldIk, TargetInsideTableGivesOnlyCollidingSolutions) {
  Workspace ws(test::feedingScene());
  Rng rng(3);
  IkOptions o;
  o.maxAttempts = 5;
  const Pose3 target{Eigen::Vector3d(0.35, 0.45, 0.10), Eigen::Quaterniond(0, 1, 0, 0)};
  const IkResult r = solveIk(ws, target, configs::kRetract, rng, o);
  EXPECT_EQ(r.status, IkStatus::InCollision);
  EXPECT_FALSE(r.collision.free());
}

TEST(WorldIk, SameSeedSameAnswer) {
  Workspace ws(test::feedingScene());
  const Pose3 target{Eigen::Vector3d(0.45, 0.2, 0.45), Eigen::Quaterniond(0, 1, 0, 0)};
  Rng a(9), b(9);
  const IkResult r1 = solveIk(ws, target, configs::kZero, a);
  const IkResult r2 = solveIk(ws, target, configs::kZero, b);
  ASSERT_TRUE(r1.solved());
  EXPECT_EQ(r1.q, r2.q);
}

}  // namespace
}  // namespace cbtl::world
