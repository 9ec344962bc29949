// Pose.h — rigid poses, planar poses and arm configurations used across the robot world.
//
// Frames: every Pose3 is "child in parent" (the parent is the world unless a function says otherwise);
// positions in metres, orientations as unit quaternions. Pose2 is a planar pose (x, y in metres, yaw in
// radians about world z). ArmConfig holds the seven Gen3 joint angles q1..q7 in radians.
#pragma once

#include "runtime/core/Rng.h"

#include <Eigen/Geometry>

#include <array>
#include <cstdint>

namespace cbtl::world {

// The robot world draws from the project's one generator (runtime/core/Rng.h: its draws are the same with
// every standard library). Every random choice draws from an Rng the caller passes in, so the same seed
// reproduces the same result.
using Rng = rt::Rng;

inline constexpr int kArmDof = 7;
using ArmConfig = std::array<double, kArmDof>;

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

struct Pose3 {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();

  static Pose3 fromPosition(const Eigen::Vector3d& p) { return {p, Eigen::Quaterniond::Identity()}; }

  // this ∘ other: `other` is expressed in this pose's frame.
  Pose3 operator*(const Pose3& other) const;
  Pose3 inverse() const;
  // A point given in this frame, returned in the parent frame.
  Eigen::Vector3d transformPoint(const Eigen::Vector3d& local) const;
};

// Wraps an angle to [-pi, pi).
double wrapAngle(double a);
// The signed shortest angular difference to - from, in [-pi, pi).
double angleDiff(double to, double from);
// Rotation angle (radians, in [0, pi]) between two orientations.
double rotationDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace cbtl::world
