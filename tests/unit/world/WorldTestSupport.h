// Shared helpers for the robot-world tests: scenes are found through CBTL_DOMAINS_DIR (set by CMake).
#pragma once

#include "robot/world/Scene.h"

#include <gtest/gtest.h>

#include <string>

namespace cbtl::world::test {

inline std::string domainsPath(const std::string& rel) { return std::string(CBTL_DOMAINS_DIR) + "/" + rel; }

// Loaded once per process and shared, as the runtime does.
inline std::shared_ptr<const Scene> feedingScene() {
  static const auto scene = Scene::loadFile(domainsPath("feeding/feeding.xml")).scene;
  return scene;
}

inline std::shared_ptr<const Scene> homeScene() {
  static const auto scene = Scene::loadFile(domainsPath("home/home.xml")).scene;
  return scene;
}

}  // namespace cbtl::world::test
