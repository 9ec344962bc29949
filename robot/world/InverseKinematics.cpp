#include "robot/world/InverseKinematics.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <vector>

namespace cbtl::world {

const char* toString(IkStatus s) {
  switch (s) {
    case IkStatus::Solved:
      return "solved";
    case IkStatus::InCollision:
      return "only colliding solutions";
    case IkStatus::NotConverged:
      return "not converged";
  }
  return "unknown";
}

ArmConfig randomConfig(const Scene& scene, Rng& rng) {
  ArmConfig q{};
  for (int i = 0; i < kArmDof; ++i) q[i] = rng.uniform(scene.armLower(i), scene.armUpper(i));
  return q;
}

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec7 = Eigen::Matrix<double, 7, 1>;
using Jac = Eigen::Matrix<double, 6, 7>;

constexpr double kProjectorRegulariser = 1e-9;
constexpr double kProgress = 1e-3;    // relative decrease of the error that counts as progress
constexpr int kStallIterations = 25;  // iterations without progress after which an attempt stops

struct ErrorTerms {
  Vec6 e;
  double pos, rot;
};

ErrorTerms poseError(const Pose3& target, const Pose3& current) {
  ErrorTerms t;
  const Eigen::Vector3d dp = target.position - current.position;
  Eigen::Quaterniond dq = target.orientation * current.orientation.conjugate();
  if (dq.w() < 0) dq.coeffs() *= -1.0;
  const Eigen::AngleAxisd aa(dq.normalized());
  const Eigen::Vector3d w = aa.angle() * aa.axis();
  t.e << dp, w;
  t.pos = dp.norm();
  t.rot = std::abs(aa.angle());
  return t;
}

// The 6x7 Jacobian (linear over angular, world frame) of `site` with respect to the arm joints.
void siteJacobian(Workspace& ws, int site, std::vector<mjtNum>& buf, Jac& J) {
  const mjModel* m = ws.model();
  mjData* d = ws.data();
  const int nv = m->nv;
  buf.resize(static_cast<size_t>(6 * nv));
  mj_comPos(m, d);  // mj_jacSite reads cdof and subtree_com, which mj_kinematics does not fill
  mj_jacSite(m, d, buf.data(), buf.data() + 3 * nv, site);
  for (int c = 0; c < kArmDof; ++c) {
    const int dof = ws.scene().armDofAdr(c);
    for (int r = 0; r < 3; ++r) {
      J(r, c) = buf[static_cast<size_t>(r * nv + dof)];
      J(r + 3, c) = buf[static_cast<size_t>(3 * nv + r * nv + dof)];
    }
  }
}

}  // namespace

IkResult solveIk(Workspace& ws, const Pose3& target, const ArmConfig& seed, Rng& rng, const IkOptions& o) {
  const Scene& s = ws.scene();
  const int site = o.site >= 0 ? o.site : s.toolSite();
  std::vector<mjtNum> buf;
  IkResult result;
  double bestScore = INFINITY;
  bool anyConverged = false;
  Jac J;
  const double lambda2 = o.damping * o.damping;

  for (int attempt = 0; attempt < o.maxAttempts; ++attempt) {
    ArmConfig q = s.normalize(attempt == 0 ? seed : randomConfig(s, rng));
    ++result.attempts;
    double attemptBest = INFINITY;
    int lastProgress = 0;
    for (int it = 0; it <= o.maxIterations; ++it) {
      ws.setArm(q);
      const ErrorTerms err = poseError(target, ws.sitePose(site));
      const double score = err.pos + 0.1 * err.rot;
      // An attempt that has stopped getting closer (a joint limit, a local minimum) gives up early.
      if (score < attemptBest * (1 - kProgress)) {
        attemptBest = score;
        lastProgress = it;
      } else if (it - lastProgress > kStallIterations) {
        break;
      }
      if (score < bestScore && !anyConverged) {
        bestScore = score;
        result.q = q;
        result.positionError = err.pos;
        result.rotationError = err.rot;
      }
      if (err.pos <= o.positionTolerance && err.rot <= o.rotationTolerance) {
        if (o.requireCollisionFree) {
          const CollisionReport rep = checkRobotCollisions(ws);
          if (!rep.free()) {
            anyConverged = true;
            result.q = q;
            result.positionError = err.pos;
            result.rotationError = err.rot;
            result.collision = rep;
            break;
          }
        }
        result.status = IkStatus::Solved;
        result.q = q;
        result.positionError = err.pos;
        result.rotationError = err.rot;
        return result;
      }
      if (it == o.maxIterations) break;
      ++result.iterations;
      siteJacobian(ws, site, buf, J);
      const Eigen::Matrix<double, 6, 6> JJt = J * J.transpose();
      const Eigen::Matrix<double, 6, 6> A = JJt + lambda2 * Eigen::Matrix<double, 6, 6>::Identity();
      Vec7 dq = J.transpose() * A.ldlt().solve(err.e);
      if (o.nullspaceGain > 0) {
        // Projector onto the null space of J: N = I - J⁺J with J⁺ = Jᵀ(JJᵀ)⁻¹ (a 6x6 solve instead of an SVD;
        // the tiny regulariser only matters at singular configurations, where the task term dominates anyway).
        Vec7 pull;
        for (int i = 0; i < kArmDof; ++i)
          pull(i) = o.nullspaceGain * (s.armContinuous(i) ? angleDiff(o.rest[i], q[i]) : (o.rest[i] - q[i]));
        const Eigen::Matrix<double, 6, 6> M = JJt + kProjectorRegulariser * Eigen::Matrix<double, 6, 6>::Identity();
        dq += pull - J.transpose() * M.ldlt().solve(J * pull);
      }
      const double biggest = dq.cwiseAbs().maxCoeff();
      if (biggest > o.maxStep) dq *= o.maxStep / biggest;
      for (int i = 0; i < kArmDof; ++i) q[i] += dq(i);
      q = s.normalize(q);
    }
  }
  result.status = anyConverged ? IkStatus::InCollision : IkStatus::NotConverged;
  ws.setArm(result.q);
  return result;
}

}  // namespace cbtl::world
