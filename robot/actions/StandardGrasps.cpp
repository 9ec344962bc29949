#include "robot/actions/StandardGrasps.h"

#include <numbers>

namespace cbtl::actions {

namespace {
// Position of site duster_grasp in the duster's body frame (home.xml): on the pole axis.
const Eigen::Vector3d kDusterGraspSite(0.0, -0.32, -0.03);
}  // namespace

world::Pose3 dusterToolInBody(int k) {
  // Metres from the head centre along the pole (the pole spans 0.04-0.39 m; the head's box ends at 0.04 m).
  static constexpr double kAlongPole[kDusterGraspPoints] = {0.32, 0.26, 0.20, 0.16, 0.36};
  const Eigen::Vector3d onPole(kDusterGraspSite.x(), -kAlongPole[k % kDusterGraspPoints], kDusterGraspSite.z());
  const double twist = k < kDusterGraspPoints ? 0.0 : kDusterGraspTwist;
  // A half turn about the body's x axis points the tool down (tool x = body x, tool y = body -y); the tilt
  // about the body's y (the pole's axis) then leans the tool's z towards the body's -x; the twist turns the
  // fingers about the tool's z, still across the pole.
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(kDusterGraspTilt, Eigen::Vector3d::UnitY())) *
                               Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX())) *
                               Eigen::Quaterniond(Eigen::AngleAxisd(twist, Eigen::Vector3d::UnitZ()));
  // The pole axis lies kDusterGraspHeight ahead of the tool frame along the tool's z.
  return world::Pose3{onPole - kDusterGraspHeight * (q * Eigen::Vector3d::UnitZ()), q};
}

world::Pose3 bookToolInBody() {
  // Tool axes in the book frame: x = book x, y = book -z, z = book +y (a quarter turn of -90 deg about x).
  const Eigen::Quaterniond q(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  return world::Pose3{Eigen::Vector3d(0, -kBookGraspDepth, 0), q};
}

int standardGraspCount(std::string_view object) { return object == "duster" ? kDusterGraspCount : 0; }

std::optional<world::Pose3> standardGraspInBody(std::string_view object, int k) {
  if (k < 0 || k >= standardGraspCount(object)) return std::nullopt;
  return dusterToolInBody(k);
}

std::optional<world::Pose3> standardGraspTool(const world::World& w, std::string_view object, int k) {
  const auto inBody = standardGraspInBody(object, k);
  const auto pose = w.workspace().objectPose(object);
  if (!inBody || !pose) return std::nullopt;
  return *pose * *inBody;
}

}  // namespace cbtl::actions
