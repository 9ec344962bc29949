#include "domains/robot/NamedConfigurations.h"

#include "runtime/world/NamedConfigurations.h"

namespace cbtl::domains::robot {

NamedConfigurations::NamedConfigurations() : table_(world::standardConfigurations()) {}

std::optional<world::ArmConfig> NamedConfigurations::find(std::string_view name) const {
  const auto it = table_.find(name);
  if (it == table_.end()) return std::nullopt;
  return it->second;
}

void NamedConfigurations::add(std::string name, const world::ArmConfig& q) { table_[std::move(name)] = q; }

std::vector<std::string> NamedConfigurations::names() const {
  std::vector<std::string> out;
  for (const auto& [name, q] : table_) out.push_back(name);
  return out;
}

}  // namespace cbtl::domains::robot
