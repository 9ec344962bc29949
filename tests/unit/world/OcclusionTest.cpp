// Occlusion of the user's view: high with the arm in front of the eyes, zero with the arm retracted.
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/Occlusion.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

TEST(WorldOcclusion, RetractedArmDoesNotOcclude) {
  Workspace ws(test::feedingScene());
  const auto spec = occlusionSpecFor(ws.scene());
  ASSERT_TRUE(spec.has_value());
  ws.setArm(configs::kRetract);
  EXPECT_EQ(occlusionScore(ws, *spec), 0.0);
}

TEST(WorldOcclusion, EyesAreWhereTheSceneSaysAndTheHeadIsExcluded) {
  Workspace ws(test::feedingScene());
  const auto spec = *occlusionSpecFor(ws.scene());
  const Pose3 eyes = ws.sitePose(spec.eyeSite);
  EXPECT_NEAR((eyes.position - Eigen::Vector3d(-0.3, 0.5, 0.77)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((eyes.orientation * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-9);
  // The rays start inside the head sphere; without the exclusion every ray would hit it at d ≈ 0.
  ws.setArm(configs::kRetract);
  OcclusionSpec noExclusion = spec;
  noExclusion.excludeBody = -1;
  EXPECT_EQ(occlusionScore(ws, noExclusion), 0.0);  // also hidden by its geom group
}

TEST(WorldOcclusion, ArmInFrontOfTheEyesOccludes) {
  Workspace ws(test::feedingScene());
  const auto spec = *occlusionSpecFor(ws.scene());
  Rng rng(8);
  // Tool 0.25 m in front of the eyes, pointing back at the face.
  const Pose3 target{Eigen::Vector3d(-0.05, 0.5, 0.77),
                     Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()))};
  const IkResult r = solveIk(ws, target, configs::kHome, rng);
  ASSERT_TRUE(r.solved()) << toString(r.status);
  const double score = occlusionScore(ws, spec);
  EXPECT_GE(score, 0.05);  // the reference user complains from 0.05
  EXPECT_LE(score, 1.0);
}

TEST(WorldOcclusion, CulledRaysMatchMujocoRay) {
  Workspace ws(test::feedingScene());
  const auto spec = *occlusionSpecFor(ws.scene());
  Rng rng(13);
  int occluding = 0;
  for (int i = 0; i < 2000; ++i) {
    ws.setArm(randomConfig(ws.scene(), rng));
    const double fast = occlusionScore(ws, spec, RayMethod::Culled);
    EXPECT_NEAR(fast, occlusionScore(ws, spec, RayMethod::MujocoRay), 1e-12);
    occluding += fast > 0 ? 1 : 0;
  }
  EXPECT_GT(occluding, 10);
}

TEST(WorldOcclusion, ArmAcrossTheFaceOccludesHeavily) {
  Workspace ws(test::feedingScene());
  const auto spec = *occlusionSpecFor(ws.scene());
  // The most occluding of 200k random collision-free configurations: the forearm and wrist across the
  // user's face, close to the eyes.
  const ArmConfig q{2.064, -0.932, -1.818, -0.408, 0.814, 1.458, 0.846};
  ASSERT_TRUE(checkArm(ws, q).free());
  EXPECT_GT(occlusionScore(ws, spec), 0.25);
}

TEST(WorldOcclusion, AbovePlateBarelyOccludes) {
  Workspace ws(test::feedingScene());
  const auto spec = *occlusionSpecFor(ws.scene());
  ws.setArm(test::feedingConf("abovePlate"));
  const double score = occlusionScore(ws, spec);
  EXPECT_GE(score, 0.0);
  EXPECT_LT(score, 0.2);
}

}  // namespace
}  // namespace cbtl::world
