#include "robot/world/PreWipe.h"

#include "robot/world/SurfaceFace.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cbtl::world {

std::optional<Pose3> preWipeToolPose(const World& w, const std::string& surface, const std::string& object,
                                     const Pose3& toolToObject, const Pose2& base) {
  const auto face = surfaceFace(w.workspace(), surface);
  const auto box = w.clearance().objectBox(object);
  if (!face || !box) return std::nullopt;
  const double dx = face->center.x() - base.x, dy = face->center.y() - base.y;
  Eigen::Vector3d p = face->center;
  double yaw = 0;
  if (std::abs(dx) >= std::abs(dy)) {
    const double s = dx >= 0 ? 1.0 : -1.0;
    p.x() = face->center.x() - s * (face->halfX - kPreWipeEdgeInset);
    const double side = std::max(0.0, face->halfY - kPreWipeSideInset);
    p.y() = std::clamp(base.y, face->center.y() - side, face->center.y() + side);
    yaw = std::atan2(0.0, s) - std::numbers::pi / 2;  // body +y along (s, 0)
  } else {
    const double s = dy >= 0 ? 1.0 : -1.0;
    p.y() = face->center.y() - s * (face->halfY - kPreWipeEdgeInset);
    const double side = std::max(0.0, face->halfX - kPreWipeSideInset);
    p.x() = std::clamp(base.x, face->center.x() - side, face->center.x() + side);
    yaw = std::atan2(s, 0.0) - std::numbers::pi / 2;  // body +y along (0, s)
  }
  const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  // Upright: the body's lowest point is box.center.z - box.halfExtents.z below its origin.
  p.z() = face->top() + kPreWipeLift - (box->center.z() - box->halfExtents.z());
  const Pose3 objectPose{p, q};
  return objectPose * toolToObject.inverse();
}

}  // namespace cbtl::world
