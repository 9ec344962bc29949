// HomeTestSupport.h — arranging home-scene worlds for the Cleaning and Books tests. The scene file is named
// explicitly (CBTL_DOMAINS_DIR, the source tree's domains/), as a program's `world` line would.
#pragma once

#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/actions/WipeSweep.h"
#include "robot/world/Scene.h"

#include "robot/world/WorldOperations.h"

#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::test {

// domains/home/home.xml, loaded once per test process; throws std::runtime_error when it cannot be loaded.
inline std::shared_ptr<const world::Scene> homeScene() {
  static const std::shared_ptr<const world::Scene> scene = [] {
    const world::SceneLoadResult r = world::Scene::loadFile(std::string(CBTL_DOMAINS_DIR) + "/home/home.xml");
    if (r.status != world::LoadStatus::Ok) throw std::runtime_error(r.message);
    return r.scene;
  }();
  return scene;
}

// Program facts that name only the home scene (the Cleaning simulator reads no item set).
inline domains::ProgramFacts homeFacts() {
  domains::ProgramFacts facts;
  facts.scenePath = std::string(CBTL_DOMAINS_DIR) + "/home/home.xml";
  facts.scene = homeScene();
  return facts;
}

// The robot at `base` holding `object` (duster: standard grasp; a book: carry grasp), arm at kHome, every
// book except a held one parked; false if the state is rejected.
inline bool holdAt(world::World& w, const std::string& object, const world::Pose2& base) {
  world::WorldState s = w.workspace().state();
  for (std::size_t k = 0; k < domains::home::kBookCount; ++k)
    s.objects[domains::home::bookBody(k)] = domains::home::parkedPose(k);
  s.base = base;
  s.held.reset();
  domains::home::holdCarried(s, object);
  return w.workspace().setState(s) == world::StateStatus::Ok;
}

// Moves the arm to a collision-free IK solution of `tool` (a few sampled seeds); false if none is found.
inline bool armTo(world::World& w, const world::Pose3& tool, world::Rng& rng) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    if (const auto q = world::builtins::sampleIk(w, tool, rng)) {
      w.workspace().setArm(*q);
      return true;
    }
  }
  return false;
}

// The robot at `base` holding the duster with the arm at the pre-wipe pose of `surface`.
inline bool readyToWipe(world::World& w, const std::string& surface, const world::Pose2& base, world::Rng& rng) {
  if (!holdAt(w, "duster", base)) return false;
  const auto tool = actions::preWipeToolPose(w, surface, "duster", w.workspace().state().held->toolToObject, base);
  return tool && armTo(w, *tool, rng);
}

// The handover tool orientation of books.cbtl: rpy(-pi/4, pi/2, 0), R = Rz(yaw) Ry(pitch) Rx(roll).
inline Eigen::Quaterniond handoverOrientation() {
  return Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(-std::numbers::pi / 4, Eigen::Vector3d::UnitX());
}

// Puts the tool (holding what it holds) at a handover point `radius` metres from `centre`, trying a few
// directions; the point reached, or nullopt.
inline std::optional<Eigen::Vector3d> handoverAt(world::World& w, const Eigen::Vector3d& centre, double radius,
                                                 world::Rng& rng) {
  const std::vector<Eigen::Vector3d> directions{{-1, 0, 0},  {-1, 0, 1}, {0, -1, 0}, {0, 0, 1},
                                                {-1, -1, 0}, {-1, 1, 0}, {0, 1, 0}};
  for (const Eigen::Vector3d& d : directions) {
    const Eigen::Vector3d p = centre + radius * d.normalized();
    if (armTo(w, world::Pose3{p, handoverOrientation()}, rng)) return w.workspace().toolPose().position;
  }
  return std::nullopt;
}

}  // namespace cbtl::test
