// NamedConfigurations.h — the arm configurations that `moveArmToNamed(name)` and std.kinova's namedConf
// know by name (radians, joint_1..joint_7), from runtime/world/WorldState.h `configs::`.
//
// Names: "home", "retract", "zero", "abovePlate", "utensilAboveMount", "drinkGaze", "homeSceneInitial"
// (the home scene's start configuration of the seed). A domain may add its own names (e.g. Feeding's
// "beforeTransfer") through NamedConfigurations::add.
#pragma once

#include "Pose.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::domains::robot {

class NamedConfigurations {
 public:
  // The standard table above.
  NamedConfigurations();

  // The configuration called `name`, or nullopt when the table has no such name.
  std::optional<world::ArmConfig> find(std::string_view name) const;
  // Adds or replaces a name.
  void add(std::string name, const world::ArmConfig& q);
  // The names in alphabetical order (for messages).
  std::vector<std::string> names() const;

 private:
  std::map<std::string, world::ArmConfig, std::less<>> table_;
};

}  // namespace cbtl::domains::robot
