#include "domains/home/HomeEpisode.h"

#include "domains/home/HomeScene.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/world/NamedConfigurations.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

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

void holdAtHome(world::WorldState& state, const std::string& object) {
  state.arm = world::configs::kHome;
  state.gripper = 0.0;
  const world::Pose3 toolInBody = object == "duster" ? actions::dusterToolInBody() : actions::bookToolInBody();
  state.held = world::Grasp{object, toolInBody.inverse()};
}

std::size_t uniformIndex(world::Rng& rng, std::size_t n) {
  return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

double uniform01(world::Rng& rng) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }

std::vector<std::size_t> shuffledIndices(world::Rng& rng, std::size_t n) {
  std::vector<std::size_t> v(n);
  std::iota(v.begin(), v.end(), std::size_t{0});
  // Fisher-Yates with our own index draws (std::shuffle's algorithm is unspecified).
  for (std::size_t i = n; i > 1; --i) std::swap(v[i - 1], v[uniformIndex(rng, i)]);
  return v;
}

}  // namespace cbtl::domains::home
