// Forward kinematics of the Gen3 model against the published test vectors (tool_frame, 1 mm).
#include "robot/world/Workspace.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <gtest/gtest.h>

namespace cbtl::world {
namespace {

std::shared_ptr<const Scene> feeding() {
  auto r = Scene::loadFile(CBTL_DOMAINS_DIR "/feeding/feeding.xml");
  EXPECT_EQ(r.status, LoadStatus::Ok) << r.message;
  return r.scene;
}

void expectNear(const Eigen::Vector3d& p, double x, double y, double z) {
  EXPECT_NEAR(p.x(), x, 1e-3);
  EXPECT_NEAR(p.y(), y, 1e-3);
  EXPECT_NEAR(p.z(), z, 1e-3);
}

TEST(WorldFk, ZeroConfiguration) {
  Workspace ws(feeding());
  expectNear(ws.forwardKinematics(configs::kZero).position, 0.0, -0.0249, 1.3074);
}

TEST(WorldFk, RetractConfiguration) {
  Workspace ws(feeding());
  expectNear(ws.forwardKinematics(configs::kRetract).position, 0.1305, 0.0014, 0.2087);
}

TEST(WorldFk, SeedConfigurations) {
  Workspace ws(feeding());
  expectNear(ws.forwardKinematics(configs::kHome).position, 0.5767, 0.0014, 0.4337);
  expectNear(ws.forwardKinematics(test::feedingConf("abovePlate")).position, 0.5013, 0.3031, 0.5317);
  expectNear(ws.forwardKinematics(test::feedingConf("utensilAboveMount")).position, 0.2389, -0.0735, 0.1683);
  expectNear(ws.forwardKinematics(test::feedingConf("drinkGaze")).position, 0.5837, -0.0003, 0.3091);
}

TEST(WorldFk, HomeSceneMobileBase) {
  auto r = Scene::loadFile(CBTL_DOMAINS_DIR "/home/home.xml");
  ASSERT_EQ(r.status, LoadStatus::Ok) << r.message;
  Workspace ws(r.scene);
  expectNear(ws.forwardKinematics(test::namedConf(*r.scene, "homeSceneInitial")).position, 0.1781, -0.2748, 0.5923);
  WorldState st;
  st.arm = configs::kZero;
  st.base = {1.0, 0.2, 0.0};
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  expectNear(ws.toolPose().position, 1.0, 0.2 - 0.0249, 1.3074);
}

}  // namespace
}  // namespace cbtl::world
