// ActionConfigurations.h — the arm configurations `moveArmToNamed(name)` knows beyond the scene's own: the
// world library's standard table (robot/world/NamedConfigurations.h: home, retract, zero, abovePlate,
// utensilAboveMount, drinkGaze, homeSceneInitial; radians, joint_1..joint_7) plus names a domain adds
// with ActionConfigurations::add. A scene's <numeric name="conf_<name>"> (Feeding's beforeTransfer) is looked
// up first by the executor, as by std.kinova's namedConf.
#pragma once

#include "robot/world/Pose.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::actions {

class ActionConfigurations {
 public:
  // The standard table above.
  ActionConfigurations();

  // The configuration called `name`, or nullopt when the table has no such name.
  std::optional<world::ArmConfig> find(std::string_view name) const;
  // Adds or replaces a name.
  void add(std::string name, const world::ArmConfig& q);
  // The names in alphabetical order (for messages).
  std::vector<std::string> names() const;

 private:
  std::map<std::string, world::ArmConfig, std::less<>> table_;
};

}  // namespace cbtl::actions
