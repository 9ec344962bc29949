// Shared helpers for the robot-world tests: scenes are found through CBTL_DOMAINS_DIR (set by CMake).
#pragma once

#include "robot/world/NamedConfigurations.h"
#include "robot/world/Scene.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

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

// The scene's named configuration (its conf_<name> numeric, else the standard table); a failed expectation
// and all zeros when the scene has none.
inline ArmConfig namedConf(const Scene& scene, std::string_view name) {
  const auto q = namedConfiguration(scene, name);
  EXPECT_TRUE(q.has_value()) << "no named configuration " << name;
  return q.value_or(ArmConfig{});
}

// Feeding's configurations (feeding.xml): abovePlate, utensilAboveMount, drinkGaze, beforeTransfer.
inline ArmConfig feedingConf(std::string_view name) { return namedConf(*feedingScene(), name); }

}  // namespace cbtl::world::test
