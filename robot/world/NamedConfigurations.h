// NamedConfigurations.h — arm configurations known by name, shared by std.kinova's namedConf and the
// moveArmToNamed action so that a plan and its constraints mean the same configuration.
//
// A scene defines its own: <numeric name="conf_<name>" size="7" data="q1 .. q7"/> (radians), e.g.
// Feeding's beforeTransfer and abovePlate, the home scene's homeSceneInitial. Those come first; then the
// standard table of WorldState.h configs, which holds only the names every scene shares: zero, home, retract.
#pragma once

#include "robot/world/Scene.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::world {

const std::map<std::string, ArmConfig, std::less<>>& standardConfigurations();

// The scene's conf_<name> numeric, else the standard entry, else nullopt.
std::optional<ArmConfig> namedConfiguration(const Scene& scene, std::string_view name);

// Every name namedConfiguration knows in `scene` (its conf_ numerics of size 7 and the standard names),
// sorted, without duplicates (for messages).
std::vector<std::string> namedConfigurationNames(const Scene& scene);

}  // namespace cbtl::world
