#include "robot/world/NamedConfigurations.h"

#include "robot/world/WorldState.h"

namespace cbtl::world {

const std::map<std::string, ArmConfig, std::less<>>& standardConfigurations() {
  static const std::map<std::string, ArmConfig, std::less<>> table = {
      {"zero", configs::kZero},
      {"home", configs::kHome},
      {"retract", configs::kRetract},
      {"abovePlate", configs::kAbovePlate},
      {"utensilAboveMount", configs::kUtensilAboveMount},
      {"drinkGaze", configs::kDrinkGaze},
      {"homeSceneInitial", configs::kHomeSceneInitial}};
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

}  // namespace cbtl::world
