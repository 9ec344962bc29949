#include "robot/world/InverseKinematics.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

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

}  // namespace

// The 6x7 Jacobian (linear over angular, world frame) of `site` with respect to the arm joints. Every arm joint
// is a hinge, so column c is (axis × (site − anchor), axis) with the joint's world axis and anchor, which the
// kinematics pass leaves in mjData (the same Jacobian mj_jacSite gives, without mj_comPos's pass over every
// body; test WorldIk.ArmJacobianEqualsMujocos).
Jac armJacobian(const Workspace& ws, int site) {
  Jac J;
  const mjData* d = ws.data();
  const Eigen::Vector3d p(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
  for (int c = 0; c < kArmDof; ++c) {
    const int j = ws.scene().armJointId(c);
    const Eigen::Vector3d axis(d->xaxis[3 * j], d->xaxis[3 * j + 1], d->xaxis[3 * j + 2]);
    const Eigen::Vector3d anchor(d->xanchor[3 * j], d->xanchor[3 * j + 1], d->xanchor[3 * j + 2]);
    J.block<3, 1>(0, c) = axis.cross(p - anchor);
    J.block<3, 1>(3, c) = axis;
  }
  return J;
}

IkResult solveIk(Workspace& ws, const Pose3& target, const ArmConfig& seed, Rng& rng, const IkOptions& o) {
  const Scene& s = ws.scene();
  const int site = o.site >= 0 ? o.site : s.toolSite();
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
          const CollisionReport rep = checkRobotCollisions(ws, o.collision);
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
      J = armJacobian(ws, site);
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
