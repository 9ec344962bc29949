#include "robot/world/NamedConfigurations.h"

#include "robot/world/WorldState.h"

#include <set>

namespace cbtl::world {

const std::map<std::string, ArmConfig, std::less<>>& standardConfigurations() {
  static const std::map<std::string, ArmConfig, std::less<>> table = {
      {"zero", configs::kZero}, {"home", configs::kHome}, {"retract", configs::kRetract}};
  return table;
}

std::optional<ArmConfig> namedConfiguration(const Scene& scene, std::string_view name) {
  const mjModel* m = scene.model();
  const int id = mj_name2id(m, mjOBJ_NUMERIC, ("conf_" + std::string(name)).c_str());
  if (id >= 0 && m->numeric_size[id] == kArmDof) {
    ArmConfig q{};
    for (int i = 0; i < kArmDof; ++i) q[i] = m->numeric_data[m->numeric_adr[id] + i];
    return q;
  }
  const auto& table = standardConfigurations();
  const auto it = table.find(name);
  if (it == table.end()) return std::nullopt;
  return it->second;
}

std::vector<std::string> namedConfigurationNames(const Scene& scene) {
  std::set<std::string> names;
  const mjModel* m = scene.model();
  constexpr std::string_view kPrefix = "conf_";
  for (int id = 0; id < m->nnumeric; ++id) {
    const std::string_view name(m->names + m->name_numericadr[id]);
    if (name.starts_with(kPrefix) && m->numeric_size[id] == kArmDof) names.emplace(name.substr(kPrefix.size()));
  }
  for (const auto& [name, q] : standardConfigurations()) names.insert(name);
  return {names.begin(), names.end()};
}

}  // namespace cbtl::world
