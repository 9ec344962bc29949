// Certified segments: a graze between samples is refused, a clear segment is certified, the motion bounds hold,
// and contact allowances are honoured only for what they name and only up to their depth.
#include "robot/world/MotionBound.h"
#include "robot/world/SegmentCertificate.h"
#include "robot/world/Separation.h"
#include "tests/unit/world/WorldTestSupport.h"

#include "robot/world/InverseKinematics.h"

#include <cmath>
#include <string>

namespace cbtl::world {
namespace {

// The mobile base drives along x at y = -0.4 from x = 0.3 to 0.9 (arm retracted). book_6 stands upright beside the
// path, turned so that one vertical edge points at the path, `gap` metres from the base stand (a cylinder of radius
// 0.1) when the base passes it at x = 0.6025 (negative gap: the edge cuts that far into the stand).
struct PassingBook {
  Workspace ws{test::homeScene()};
  Pose2 from{0.3, -0.4, 0.0}, to{0.9, -0.4, 0.0};
  explicit PassingBook(double gap) {
    WorldState st;
    st.arm = configs::kRetract;
    st.base = from;
    EXPECT_EQ(ws.setState(st), StateStatus::Ok);
    // The book's corner (0.02, -0.05) turned by yaw points straight down -y, 0.05385 m from its centre.
    const double yaw = -(std::atan2(0.02, 0.05));
    const double corner = std::hypot(0.02, 0.05);
    const Eigen::Vector3d centre(0.6025, -0.4 + 0.1 + gap + corner, -0.2);
    const Pose3 pose{centre, Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))};
    EXPECT_EQ(ws.setObjectPose("book_6", pose), StateStatus::Ok);
  }
};

TEST(WorldSegmentCertificate, RefusesAGrazeTheSampledCheckMisses) {
  PassingBook scene(-0.00002);  // the stand's edge passes 0.02 mm into the book's corner
  Workspace& ws = scene.ws;
  // The old check: states every 5 mm along the segment (0.005, its default resolution). Every one is free,
  // exactly measured: the graze lies between two samples.
  for (int k = 0; k <= 120; ++k) {
    const double t = k / 120.0;
    ws.setBase({scene.from.x + t * (scene.to.x - scene.from.x), -0.4, 0.0});
    ASSERT_TRUE(checkRobotCollisions(ws).free()) << "sample " << k << ": " << checkRobotCollisions(ws).second;
  }
  const SegmentReport r = certifyBaseSegment(ws, scene.from, scene.to);
  EXPECT_FALSE(r.free());
  EXPECT_EQ(r.status, SegmentStatus::Collides);
  EXPECT_EQ(r.contact.second, "book_6_geom");
  EXPECT_NEAR(scene.from.x + r.at * 0.6, 0.6025, 0.003);  // found where the corner is
}

TEST(WorldSegmentCertificate, CertifiesTheSameMotionOneMillimetreClear) {
  PassingBook scene(0.001);
  const SegmentReport r = certifyBaseSegment(scene.ws, scene.from, scene.to);
  EXPECT_TRUE(r.free()) << toString(r.status) << " " << r.contact.first << " / " << r.contact.second;
  EXPECT_GT(r.states, 2);  // it had to look closer near the book
  // Reversed, too.
  EXPECT_TRUE(certifyBaseSegment(scene.ws, scene.to, scene.from).free());
}

TEST(WorldSegmentCertificate, ArmSegmentThroughTheTableIsRefusedAndAClearOneCertified) {
  Workspace ws(test::feedingScene());
  // Both ends free; the straight joint segment between them passes through a configuration with the gripper 2.5 cm
  // into the table top (WorldCollision.ArmThroughTableCollides): one joint turned either way from it, far enough
  // that both ends are clear.
  const ArmConfig inTable{-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004};
  ASSERT_FALSE(checkArm(ws, inTable).free());
  ArmConfig above{}, turned{};
  bool found = false;
  for (int j = 0; j < kArmDof && !found; ++j) {
    for (double delta : {0.3, 0.6, 0.9, 1.2}) {
      above = inTable;
      turned = inTable;
      above[j] += delta;
      turned[j] -= delta;
      found = ws.scene().withinLimits(above) && ws.scene().withinLimits(turned) && checkArm(ws, above).free() &&
              checkArm(ws, turned).free();
      if (found) break;
    }
  }
  ASSERT_TRUE(found) << "no joint turns the gripper out of the table both ways";
  bool sampledContact = false;  // dense exact sampling, independent of the certificate, finds the contact
  for (int k = 0; k <= 2000 && !sampledContact; ++k) {
    ArmConfig q{};
    for (int i = 0; i < kArmDof; ++i) q[i] = above[i] + (turned[i] - above[i]) * k / 2000.0;
    sampledContact = !checkArm(ws, q).free();
  }
  ASSERT_TRUE(sampledContact);
  const SegmentReport through = certifyArmSegment(ws, above, turned);
  EXPECT_EQ(through.status, SegmentStatus::Collides);
  const SegmentReport home = certifyArmSegment(ws, configs::kHome, configs::kRetract);
  EXPECT_TRUE(home.free()) << home.contact.first << " / " << home.contact.second;
}

// The motion bound is a true bound: over random short arm segments, no geom's centre (a point of the geom) moves
// more than the sum of |Δq_k| times its rate.
TEST(WorldSegmentCertificate, MotionBoundsBoundEveryGeomsDisplacement) {
  Workspace ws(test::homeScene());
  const Scene& s = ws.scene();
  const MotionBound& mb = s.motionBound();
  Rng rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    const ArmConfig a = randomConfig(s, rng);
    ArmConfig b = a;
    for (int i = 0; i < kArmDof; ++i) b[i] = s.normalize(a)[i] + rng.uniform(-0.3, 0.3);
    b = s.normalize(b);
    ws.setArm(a);
    std::vector<Eigen::Vector3d> before;
    for (int g : s.robotGeoms()) before.emplace_back(ws.data()->geom_xpos + 3 * g);
    ws.setArm(b);
    for (std::size_t n = 0; n < s.robotGeoms().size(); ++n) {
      const int g = s.robotGeoms()[n];
      const int body = s.model()->geom_bodyid[g];
      double bound = 0;
      for (int i = 0; i < kArmDof; ++i) {
        const double dq = s.armContinuous(i) ? std::abs(angleDiff(b[i], a[i])) : std::abs(b[i] - a[i]);
        const double* p = s.model()->geom_pos + 3 * g;
        bound += dq * mb.rate(mb.jointIndex(s.armJointId(i)), body, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
      }
      const double moved = (Eigen::Vector3d(ws.data()->geom_xpos + 3 * g) - before[n]).norm();
      ASSERT_LE(moved, bound + 1e-12) << s.geomName(g) << " trial " << trial;
    }
  }
}

// A held book lowered onto a shelf face: touching the face is contact (refused) unless an allowance names that
// face, and then only up to the allowed depth; an allowance for one face does not cover another.
TEST(WorldSegmentCertificate, ContactAllowancesAreHonouredOnlyForWhatTheyName) {
  Workspace ws(test::homeScene());
  WorldState st;
  st.base = {0.0, -0.2, 0.0};
  st.arm = configs::kRetract;
  ASSERT_EQ(ws.setState(st), StateStatus::Ok);
  ASSERT_TRUE(checkRobotCollisions(ws).free()) << checkRobotCollisions(ws).second;
  const int shelf = ws.scene().geomId("shelf_layer_1");
  ASSERT_GE(shelf, 0);
  // Re-attaches the book so that it stands on the shelf's top face, `depth` metres into it, beside the other books.
  auto holdAtDepth = [&](double depth) {
    ASSERT_EQ(ws.setHeld(std::nullopt), StateStatus::Ok);
    const double top = ws.data()->geom_xpos[3 * shelf + 2] + ws.model()->geom_size[3 * shelf + 2];
    const Eigen::Vector3d centre(ws.data()->geom_xpos + 3 * shelf);
    ASSERT_EQ(ws.setObjectPose("book_4", Pose3::fromPosition({centre.x() + 0.3, centre.y(), top + 0.08 - depth})),
              StateStatus::Ok);
    ASSERT_EQ(ws.setHeld(std::string("book_4")), StateStatus::Ok);
  };
  ContactAllowance onShelf;
  onShelf.geom = shelf;
  onShelf.separation = -0.001;
  CollisionOptions allowed;
  allowed.allowances = {onShelf};
  ContactAllowance elsewhere = onShelf;
  elsewhere.geom = ws.scene().geomId("shelf_layer_2");
  CollisionOptions other;
  other.allowances = {elsewhere};

  holdAtDepth(0.0005);  // half a millimetre into the shelf's top
  const auto plain = checkRobotCollisions(ws);
  EXPECT_EQ(plain.status, CollisionStatus::HeldObject);
  EXPECT_EQ(plain.second, "shelf_layer_1");
  EXPECT_NEAR(plain.depth, 0.0005, 2e-5);
  EXPECT_TRUE(checkRobotCollisions(ws, allowed).free()) << checkRobotCollisions(ws, allowed).second;
  EXPECT_FALSE(checkRobotCollisions(ws, other).free());
  holdAtDepth(0.0);  // resting exactly on the face: touching is contact too
  EXPECT_FALSE(checkRobotCollisions(ws).free());
  EXPECT_TRUE(checkRobotCollisions(ws, allowed).free());
  holdAtDepth(0.002);  // deeper than allowed
  const auto deep = checkRobotCollisions(ws, allowed);
  EXPECT_EQ(deep.status, CollisionStatus::HeldObject);
  EXPECT_NEAR(deep.depth, 0.001, 2e-5);  // 2 mm in, 1 mm allowed
}

}  // namespace
}  // namespace cbtl::world
