#include "domains/home/HomeScene.h"

#include <stdexcept>
#include <string>

namespace cbtl::domains::home {

namespace {
constexpr double kParkX = 20.0, kParkY = 20.0, kParkSpacing = 0.5, kParkZ = 0.5;
constexpr double kParkedBeyond = 10.0;  // metres: nothing of the room lies this far out
}  // namespace

std::shared_ptr<const world::Scene> programScene(const ProgramFacts& program, std::string_view domain) {
  if (program.scene) return program.scene;
  if (program.scenePath.empty()) {
    throw std::invalid_argument(std::string(domain) +
                                ": no scene: a robot domain's simulator needs the program's `world \"...\"` scene");
  }
  std::vector<world::BodyClearance> clearances;
  for (const ir::Clearance& c : program.clearances)
    clearances.push_back({c.name, c.bodies, c.distance, whereOf(c.span)});
  const world::SceneLoadResult r = world::Scene::loadFile(program.scenePath, clearances);
  if (r.status != world::LoadStatus::Ok) throw std::runtime_error(std::string(domain) + " scene: " + r.message);
  return r.scene;
}

world::Pose3 parkedPose(std::size_t slot) {
  return world::Pose3::fromPosition(Eigen::Vector3d(kParkX + kParkSpacing * static_cast<double>(slot), kParkY, kParkZ));
}

bool isParked(const world::Pose3& pose) { return pose.position.x() > kParkedBeyond; }

}  // namespace cbtl::domains::home
