#include "app/ObservationFile.h"

#include "app/repl/ValueSyntax.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace cbtl::app {

namespace {

// The JSON value in the boundary's form, by its JSON type alone (the declaration checks it afterwards).
std::optional<sim::Value> valueOf(const nlohmann::json& j) {
  if (j.is_boolean()) return sim::Value::num(j.get<bool>() ? 1 : 0);
  if (j.is_number()) return sim::Value::num(j.get<double>());
  if (j.is_string()) return sim::Value::name(j.get<std::string>());
  if (!j.is_array()) return std::nullopt;
  if (std::all_of(j.begin(), j.end(), [](const auto& e) { return e.is_number(); }) && !j.empty()) {
    std::vector<double> v;
    for (const auto& e : j) v.push_back(e.get<double>());
    return sim::Value::vec(std::move(v));
  }
  if (std::all_of(j.begin(), j.end(), [](const auto& e) { return e.is_string(); })) {
    std::vector<std::string> members;
    for (const auto& e : j) members.push_back(e.get<std::string>());
    return sim::Value::names(std::move(members));
  }
  return std::nullopt;
}

std::string pointer(const std::string& key) {
  std::string escaped;
  for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return "/" + escaped;
}

}  // namespace

sim::Observation readObservationEntries(const std::string& path, const rt::Program& program) {
  std::ifstream in(path);
  if (!in) throw ObservationFileError(fmt::format("{}: cannot read the observation file", path));
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw ObservationFileError(fmt::format("{}: not JSON (at byte {})", path, e.byte));
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
                                             pointer(key), key, known.empty() ? "none" : known));
    }
    std::optional<sim::Value> value = valueOf(json);
    std::string error;
    if (!value) error = fmt::format("expected {}", repl::describeType(program, slot->second.type));
    if (value && !repl::coerceTo(program, slot->second.type, *value, error)) value.reset();
    if (!value) throw ObservationFileError(fmt::format("{}: {}: {}", path, pointer(key), error));
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
