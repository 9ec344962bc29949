// The tool moved along its straight line: every waypoint on the line and collision-free, small joint steps, the
// Workspace left as it was, an honest failure where the line enters an obstacle, and a bounded step count.
#include "robot/world/CartesianPath.h"
#include "robot/world/Collision.h"
#include "robot/world/MotionPlanner.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbtl::world {
namespace {

// Distance from p to the segment [a, b].
double distanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

TEST(WorldCartesianPath, FollowsTheToolLineInFreeSpace) {
  Workspace ws(test::feedingScene());
  ws.setArm(test::feedingConf("abovePlate"));
  const WorldState before = ws.state();
  const Pose3 from = ws.toolPose();
  const Pose3 target{from.position + Eigen::Vector3d(0.0, 0.06, 0.05), from.orientation};
  const auto path = cartesianToolPath(ws, target, IkOptions{});
  ASSERT_TRUE(path.has_value());
  EXPECT_EQ(ws.state().arm, before.arm);  // the Workspace is left as it was
  EXPECT_EQ(path->front(), before.arm);
  ASSERT_GE(path->size(), 8U);  // 7.8 cm in steps of at most 1 cm
  const JointSpace space = armSpace(ws.scene());
  for (std::size_t k = 0; k < path->size(); ++k) {
    const ArmConfig& q = (*path)[k];
    EXPECT_TRUE(checkArm(ws, q).free()) << "waypoint " << k;
    EXPECT_LT(distanceToSegment(ws.forwardKinematics(q).position, from.position, target.position), 2e-3)
        << "waypoint " << k << " leaves the line";
    if (k > 0) {
      const ArmConfig& p = (*path)[k - 1];
      EXPECT_LE(linfDistance(space, Waypoint(p.begin(), p.end()), Waypoint(q.begin(), q.end())), 0.25);
    }
  }
  const Pose3 end = ws.forwardKinematics(path->back());
  EXPECT_LT((end.position - target.position).norm(), 1e-3);
  EXPECT_LT(rotationDistance(end.orientation, target.orientation), 1e-2);
}

TEST(WorldCartesianPath, ALineIntoTheTableFailsAndLeavesTheStateAsItWas) {
  Workspace ws(test::feedingScene());
  ws.setArm(test::feedingConf("abovePlate"));
  const WorldState before = ws.state();
  const Pose3 from = ws.toolPose();
  const Pose3 intoTable{from.position - Eigen::Vector3d(0.0, 0.0, 0.5), from.orientation};
  EXPECT_FALSE(cartesianToolPath(ws, intoTable, IkOptions{}).has_value());
  EXPECT_EQ(ws.state().arm, before.arm);
  EXPECT_EQ(ws.toolPose().position, from.position);
}

TEST(WorldCartesianPath, TheStepCountIsBounded) {
  Workspace ws(test::feedingScene());
  ws.setArm(test::feedingConf("abovePlate"));
  const Pose3 from = ws.toolPose();
  CartesianPathOptions capped;
  capped.maxSteps = 3;
  capped.maxJointStep = 1.0;  // three steps of 2 cm each are still small joint moves
  const Pose3 target{from.position + Eigen::Vector3d(0.0, 0.06, 0.0), from.orientation};
  const auto path = cartesianToolPath(ws, target, IkOptions{}, capped);
  ASSERT_TRUE(path.has_value());
  EXPECT_EQ(path->size(), 4U);  // the start and three steps, not six
  // A non-finite target is one step, whose IK fails: no unbounded loop.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(cartesianToolPath(ws, Pose3{Eigen::Vector3d(nan, 0, 0), from.orientation}, IkOptions{}).has_value());
}

}  // namespace
}  // namespace cbtl::world
