#include "robot/actions/StandardGrasps.h"

#include <numbers>

namespace cbtl::actions {

namespace {
// Position of site duster_grasp in the duster's body frame (home.xml): on the pole axis.
const Eigen::Vector3d kDusterGraspSite(0.0, -0.32, -0.03);
}  // namespace

world::Pose3 dusterToolInBody() {
  // A half turn about the body's x axis points the tool down (tool x = body x, tool y = body -y); the tilt
  // about the body's y then leans the tool's z towards the body's -x.
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(kDusterGraspTilt, Eigen::Vector3d::UnitY())) *
                               Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()));
  // The pole axis lies kDusterGraspHeight ahead of the tool frame along the tool's z.
  return world::Pose3{kDusterGraspSite - kDusterGraspHeight * (q * Eigen::Vector3d::UnitZ()), q};
}

world::Pose3 bookToolInBody() {
  // Tool axes in the book frame: x = book x, y = book -z, z = book +y (a quarter turn of -90 deg about x).
  const Eigen::Quaterniond q(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  return world::Pose3{Eigen::Vector3d(0, -kBookGraspDepth, 0), q};
}

std::optional<world::Pose3> standardGraspTool(const world::World& w, std::string_view object) {
  if (object != "duster") return std::nullopt;
  const auto pose = w.workspace().objectPose(object);
  if (!pose) return std::nullopt;
  return *pose * dusterToolInBody();
}

}  // namespace cbtl::actions
