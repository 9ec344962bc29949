// One shared Scene, one Workspace per thread: concurrent planning and IK give the same answers as serial
// runs with the same seeds.
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <thread>

namespace cbtl::world {
namespace {

struct Outcome {
  std::vector<ArmConfig> path;
  ArmConfig ik{};
};

Outcome work(const std::shared_ptr<const Scene>& scene, std::uint64_t seed) {
  Workspace ws(scene);
  Rng rng(seed);
  Outcome o;
  o.path = planArm(ws, configs::kRetract, test::feedingConf("abovePlate"), rng).path;
  o.ik = solveIk(ws, ws.forwardKinematics(test::feedingConf("drinkGaze")), configs::kRetract, rng).q;
  return o;
}

TEST(WorldThreads, ConcurrentWorkspacesMatchSerialRuns) {
  const auto scene = test::feedingScene();
  const Outcome serialA = work(scene, 21), serialB = work(scene, 22);
  Outcome a, b;
  std::thread ta([&] { a = work(scene, 21); });
  std::thread tb([&] { b = work(scene, 22); });
  ta.join();
  tb.join();
  EXPECT_EQ(a.path, serialA.path);
  EXPECT_EQ(b.path, serialB.path);
  EXPECT_EQ(a.ik, serialA.ik);
  EXPECT_EQ(b.ik, serialB.ik);
}

}  // namespace
}  // namespace cbtl::world
