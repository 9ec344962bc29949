#include "robot/actions/ActionConfigurations.h"

#include "robot/world/NamedConfigurations.h"

namespace cbtl::actions {

ActionConfigurations::ActionConfigurations() : table_(world::standardConfigurations()) {}

std::optional<world::ArmConfig> ActionConfigurations::find(std::string_view name) const {
  const auto it = table_.find(name);
  if (it == table_.end()) return std::nullopt;
  return it->second;
}

void ActionConfigurations::add(std::string name, const world::ArmConfig& q) { table_[std::move(name)] = q; }

std::vector<std::string> ActionConfigurations::names() const {
  std::vector<std::string> out;
  for (const auto& [name, q] : table_) out.push_back(name);
  return out;
}

}  // namespace cbtl::actions
