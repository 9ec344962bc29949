#include "domains/home/HomeEpisode.h"

#include "domains/home/HomeScene.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/world/NamedConfigurations.h"

#include <stdexcept>
#include <string>

namespace cbtl::domains::home {

std::string bookBody(std::size_t k) { return "book_" + std::to_string(k); }

world::ArmConfig initialArm(const world::Scene& scene) {
  const auto named = world::namedConfiguration(scene, "homeSceneInitial");
  if (!named) throw std::runtime_error("the home scene has no conf_homeSceneInitial numeric of size 7");
  return *named;
}

world::WorldState emptyRoom(const world::Scene& scene, const std::map<std::string, world::Pose3>& scenePoses) {
  world::WorldState s;
  s.base = world::Pose2{0, 0, 0};
  s.arm = initialArm(scene);
  s.gripper = 1.0;
  s.objects = scenePoses;
  for (std::size_t k = 0; k < kBookCount; ++k) s.objects[bookBody(k)] = parkedPose(k);
  return s;
}

void holdCarried(world::WorldState& state, const std::string& object) {
  state.arm = object == "duster" ? world::configs::kHome : world::configs::kRetract;
  state.gripper = 0.0;
  const world::Pose3 toolInBody = object == "duster" ? actions::dusterToolInBody() : actions::bookToolInBody();
  state.held = world::Grasp{object, toolInBody.inverse()};
}

void caregiverReset(world::WorldState& state, const world::Scene& scene) {
  state.base = world::Pose2{0, 0, 0};
  const std::string held = state.held ? state.held->object : std::string();
  state.held.reset();
  state.gripper = 1.0;
  state.arm = initialArm(scene);
  if (held == "duster") {
    holdCarried(state, held);
  } else if (!held.empty()) {
    for (std::size_t k = 0; k < kBookCount; ++k)
      if (bookBody(k) == held) state.objects[held] = parkedPose(k);
  }
}

}  // namespace cbtl::domains::home
