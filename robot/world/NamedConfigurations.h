// NamedConfigurations.h — arm configurations known by name, shared by std.kinova's namedConf and the
// moveArmToNamed action so that a plan and its constraints mean the same configuration.
//
// A scene may define its own: <numeric name="conf_<name>" size="7" data="q1 .. q7"/> (radians), e.g.
// Feeding's beforeTransfer. Those come first; then the standard table of WorldState.h configs: zero, home,
// retract, abovePlate, utensilAboveMount, drinkGaze, homeSceneInitial.
#pragma once

#include "robot/world/Scene.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace cbtl::world {

const std::map<std::string, ArmConfig, std::less<>>& standardConfigurations();

// The scene's conf_<name> numeric, else the standard entry, else nullopt.
std::optional<ArmConfig> namedConfiguration(const Scene& scene, std::string_view name);

}  // namespace cbtl::world
