// The Workspace's subtree kinematics (arm, base, held object) against a full mj_kinematics pass, and the analytic
// arm Jacobian against mj_jacSite.
#include "robot/world/InverseKinematics.h"
#include "robot/world/SubtreeKinematics.h"
#include "robot/world/Workspace.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <gtest/gtest.h>

#include <vector>

namespace cbtl::world {
namespace {

constexpr double kTol = 1e-12;

void expectArraysNear(const mjtNum* a, const mjtNum* b, int n, const char* what, int index) {
  for (int k = 0; k < n; ++k) ASSERT_NEAR(a[k], b[k], kTol) << what << " " << index << " component " << k;
}

// Every pose the kinematics fills in the Workspace's mjData equals a fresh full pass over the same qpos.
void expectMatchesFullPass(const Workspace& ws) {
  const mjModel* m = ws.model();
  mjData* fresh = mj_makeData(m);
  mju_copy(fresh->qpos, ws.data()->qpos, m->nq);
  mj_kinematics(m, fresh);
  const mjData* d = ws.data();
  for (int b = 0; b < m->nbody; ++b) {
    expectArraysNear(d->xpos + 3 * b, fresh->xpos + 3 * b, 3, "body xpos", b);
    expectArraysNear(d->xmat + 9 * b, fresh->xmat + 9 * b, 9, "body xmat", b);
    expectArraysNear(d->xipos + 3 * b, fresh->xipos + 3 * b, 3, "body xipos", b);
  }
  for (int j = 0; j < m->njnt; ++j) {
    expectArraysNear(d->xanchor + 3 * j, fresh->xanchor + 3 * j, 3, "joint anchor", j);
    expectArraysNear(d->xaxis + 3 * j, fresh->xaxis + 3 * j, 3, "joint axis", j);
  }
  for (int g = 0; g < m->ngeom; ++g) {
    expectArraysNear(d->geom_xpos + 3 * g, fresh->geom_xpos + 3 * g, 3, "geom xpos", g);
    expectArraysNear(d->geom_xmat + 9 * g, fresh->geom_xmat + 9 * g, 9, "geom xmat", g);
  }
  for (int s = 0; s < m->nsite; ++s) {
    expectArraysNear(d->site_xpos + 3 * s, fresh->site_xpos + 3 * s, 3, "site xpos", s);
    expectArraysNear(d->site_xmat + 9 * s, fresh->site_xmat + 9 * s, 9, "site xmat", s);
  }
  mj_deleteData(fresh);
}

TEST(SubtreeKinematics, HomeSceneHasArmBaseAndObjectSubtrees) {
  const auto scene = test::homeScene();
  ASSERT_TRUE(scene);
  EXPECT_TRUE(scene->armSubtree().supported());
  EXPECT_TRUE(scene->baseSubtree().supported());
  // The arm's subtree is part of the base's, which is a strict part of the scene.
  EXPECT_LT(scene->armSubtree().bodies().size(), scene->baseSubtree().bodies().size());
  EXPECT_LT(static_cast<int>(scene->baseSubtree().bodies().size()), scene->model()->nbody - 1);
  for (size_t i = 0; i < scene->objects().size(); ++i) {
    EXPECT_TRUE(scene->objectSubtree(static_cast<int>(i)).supported());
    EXPECT_EQ(scene->objectSubtree(static_cast<int>(i)).root(), scene->objects()[i].body);
  }
}

TEST(SubtreeKinematics, ArmBaseAndHeldObjectMovesEqualAFullPass) {
  const auto scene = test::homeScene();
  ASSERT_TRUE(scene);
  Workspace ws(scene);
  Rng rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    ws.setBase({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-3, 3)});
    ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
    ws.setArm(randomConfig(*scene, rng));
    ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
  }
  // A held object follows the tool through arm and base moves.
  ASSERT_EQ(ws.setHeld(std::string("book_4")), StateStatus::Ok);
  for (int trial = 0; trial < 50; ++trial) {
    ws.setArm(randomConfig(*scene, rng));
    ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
    ws.setBase({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-3, 3)});
    ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
  }
  ASSERT_EQ(ws.setHeld(std::nullopt), StateStatus::Ok);
  const Pose3 moved{Eigen::Vector3d(0.3, -0.2, 0.9),
                    Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, 0.4, 0.5).normalized()))};
  ASSERT_EQ(ws.setObjectPose("book_2", moved), StateStatus::Ok);
  ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
}

TEST(SubtreeKinematics, FeedingSceneWithoutMobileBaseEqualsAFullPass) {
  const auto scene = test::feedingScene();
  ASSERT_TRUE(scene);
  EXPECT_FALSE(scene->baseSubtree().supported());
  Workspace ws(scene);
  Rng rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    ws.setArm(randomConfig(*scene, rng));
    ASSERT_NO_FATAL_FAILURE(expectMatchesFullPass(ws));
  }
}

TEST(WorldIk, ArmJacobianEqualsMujocos) {
  const auto scene = test::homeScene();
  ASSERT_TRUE(scene);
  Workspace ws(scene);
  Rng rng(3);
  const mjModel* m = scene->model();
  std::vector<mjtNum> jacp(static_cast<size_t>(3 * m->nv)), jacr(static_cast<size_t>(3 * m->nv));
  for (int trial = 0; trial < 30; ++trial) {
    ws.setBase({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-3, 3)});
    ws.setArm(randomConfig(*scene, rng));
    const auto J = armJacobian(ws, scene->toolSite());
    mj_comPos(m, ws.data());
    mj_jacSite(m, ws.data(), jacp.data(), jacr.data(), scene->toolSite());
    for (int c = 0; c < kArmDof; ++c) {
      const int dof = scene->armDofAdr(c);
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(J(r, c), jacp[static_cast<size_t>(r * m->nv + dof)], 1e-10) << "linear row " << r << " joint " << c;
        EXPECT_NEAR(J(r + 3, c), jacr[static_cast<size_t>(r * m->nv + dof)], 1e-10) << "angular row " << r;
      }
    }
  }
}

}  // namespace
}  // namespace cbtl::world
