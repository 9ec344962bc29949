// InverseKinematics.h — position-and-orientation IK of the Gen3 tool site by damped least squares.
//
// Each attempt iterates  dq = Jᵀ(JJᵀ + λ²I)⁻¹ e  +  N (k (q_rest - q)),  where e = [p* - p; ω] (ω the world
// rotation vector taking the current tool orientation to the target), J the 6x7 site Jacobian and
// N = I - J⁺J the null-space projector (J⁺ = Jᵀ(JJᵀ)⁻¹, regularised by 1e-9 for singular J), so the posture
// pull toward `rest` does not leak into the task. An attempt that stops making progress (its error has not
// fallen by 0.1 % in 25 iterations) ends early. Steps are clamped (largest component <= maxStep), continuous joints
// wrapped to [-pi, pi), limited joints clipped. The first attempt starts at `seed`; restarts start at uniform random
// configurations drawn from the caller's Rng. Budgets are iteration counts only.
// The target is the pose of `site` (tool_frame by default) in world coordinates, for the Workspace's
// current base pose and objects. The Workspace is left at the returned configuration.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/Workspace.h"

namespace cbtl::world {

enum class IkStatus {
  Solved,        // within tolerance, in limits (and collision-free when requested)
  InCollision,   // converged at least once, but every converged solution collided
  NotConverged,  // the iteration budget ran out without reaching the tolerance
};

const char* toString(IkStatus s);

struct IkOptions {
  int maxIterations = 150;             // per attempt
  int maxAttempts = 20;                // 1 + restarts
  double damping = 0.05;               // λ
  double maxStep = 0.3;                // rad, largest joint change per iteration
  double positionTolerance = 1e-3;     // m
  double rotationTolerance = 1e-2;     // rad
  double nullspaceGain = 0.05;         // k; 0 disables the posture term
  ArmConfig rest = configs::kRetract;  // posture the null-space term pulls toward
  bool requireCollisionFree = true;
  CollisionOptions collision;  // what collision-free means (the contacts an action allows)
  int site = -1;               // -1: the tool_frame site
};

struct IkResult {
  IkStatus status = IkStatus::NotConverged;
  ArmConfig q{};  // the solution (or the best configuration seen)
  int attempts = 0;
  int iterations = 0;          // total over attempts
  double positionError = 0.0;  // m, of q
  double rotationError = 0.0;  // rad, of q
  CollisionReport collision;   // the last collision found when status == InCollision
  bool solved() const { return status == IkStatus::Solved; }
};

IkResult solveIk(Workspace& ws, const Pose3& target, const ArmConfig& seed, Rng& rng, const IkOptions& options = {});

// The 6x7 Jacobian of `site`'s world position (rows 0-2) and orientation (rows 3-5) with respect to the seven arm
// joints, at the Workspace's current state.
Eigen::Matrix<double, 6, kArmDof> armJacobian(const Workspace& ws, int site);

// A uniformly random configuration within the joint ranges (continuous joints in [-pi, pi)).
ArmConfig randomConfig(const Scene& scene, Rng& rng);

}  // namespace cbtl::world
