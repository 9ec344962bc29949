#include "app/ObservationFile.h"

#include "app/JsonValues.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace cbtl::app {

sim::Observation readObservationEntries(const std::string& path, const rt::Program& program) {
  nlohmann::json root;
  try {
    root = readJsonFile(path, "observation file");
  } catch (const std::runtime_error& e) {
    throw ObservationFileError(e.what());
  }
  if (!root.is_object())
    throw ObservationFileError(fmt::format("{}: expected an object of observations by name", path));
  const auto& slots = program.observationSlots();
  sim::Observation entries;
  for (const auto& [key, json] : root.items()) {
    const auto slot = slots.find(key);
    if (slot == slots.end()) {
      std::string known;
      for (const auto& [name, s] : slots) known += (known.empty() ? "" : ", ") + name;
      throw ObservationFileError(fmt::format("{}: {}: the program has no observation '{}' (it has: {})", path,
                                             jsonPointer(key), key, known.empty() ? "none" : known));
    }
    std::string error;
    std::optional<sim::Value> value = valueFromJson(program, slot->second.type, json, error);
    if (!value) throw ObservationFileError(fmt::format("{}: {}: {}", path, jsonPointer(key), error));
    entries[key] = std::move(*value);
  }
  return entries;
}

sim::Observation readObservationFile(const std::string& path, const rt::Program& program, sim::Observation base) {
  const bool everyObservationGiven = base.empty();
  for (auto& [key, value] : readObservationEntries(path, program)) base[key] = std::move(value);
  if (everyObservationGiven) {
    const auto& slots = program.observationSlots();
    std::string missing;
    for (const auto& [name, slot] : slots)
      if (!base.count(name)) missing += (missing.empty() ? "" : ", ") + name;
    if (!missing.empty())
      throw ObservationFileError(
          fmt::format("{}: no value for {} (with no simulator for the domain, the file must give every observation)",
                      path, missing));
  }
  return base;
}

}  // namespace cbtl::app
