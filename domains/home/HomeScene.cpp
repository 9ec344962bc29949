#include "domains/home/HomeScene.h"

#include <stdexcept>

namespace cbtl::domains::home {

namespace {
constexpr double kParkX = 20.0, kParkY = 20.0, kParkSpacing = 0.5, kParkZ = 0.5;
constexpr double kParkedBeyond = 10.0;  // metres: nothing of the room lies this far out
}  // namespace

const std::string& homeScenePath() {
  static const std::string path = CBTL_HOME_SCENE_PATH;
  return path;
}

std::shared_ptr<const world::Scene> homeScene() {
  // A function-local static initialises once even with concurrent first calls.
  static const std::shared_ptr<const world::Scene> scene = [] {
    world::SceneLoadResult r = world::Scene::loadFile(homeScenePath());
    if (r.status != world::LoadStatus::Ok) throw std::runtime_error("home scene: " + r.message);
    return r.scene;
  }();
  return scene;
}

world::Pose3 parkedPose(std::size_t slot) {
  return world::Pose3::fromPosition(Eigen::Vector3d(kParkX + kParkSpacing * static_cast<double>(slot), kParkY, kParkZ));
}

bool isParked(const world::Pose3& pose) { return pose.position.x() > kParkedBeyond; }

}  // namespace cbtl::domains::home
