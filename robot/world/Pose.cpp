#include "robot/world/Pose.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cbtl::world {

Pose3 Pose3::operator*(const Pose3& other) const {
  return {position + orientation * other.position, (orientation * other.orientation).normalized()};
}

Pose3 Pose3::inverse() const {
  const Eigen::Quaterniond inv = orientation.conjugate();
  return {-(inv * position), inv};
}

Eigen::Vector3d Pose3::transformPoint(const Eigen::Vector3d& local) const { return position + orientation * local; }

double wrapAngle(double a) {
  constexpr double twoPi = 2.0 * std::numbers::pi;
  double r = std::fmod(a + std::numbers::pi, twoPi);
  if (r < 0) r += twoPi;
  return r - std::numbers::pi;
}

double angleDiff(double to, double from) { return wrapAngle(to - from); }

double rotationDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const double d = std::abs(a.normalized().dot(b.normalized()));
  return 2.0 * std::acos(std::min(1.0, d));
}

}  // namespace cbtl::world
