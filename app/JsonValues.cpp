#include "app/JsonValues.h"

#include "app/repl/ValueSyntax.h"
#include "support/InputFile.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cbtl::app {

namespace {

// The JSON value in the boundary's form, by its JSON type alone (the declaration checks it afterwards).
std::optional<sim::Value> shapeOf(const nlohmann::json& j) {
  if (j.is_boolean()) return sim::Value::num(j.get<bool>() ? 1 : 0);
  if (j.is_number()) return sim::Value::num(j.get<double>());
  if (j.is_string()) return sim::Value::name(j.get<std::string>());
  if (!j.is_array()) return std::nullopt;
  if (!j.empty() && std::all_of(j.begin(), j.end(), [](const auto& e) { return e.is_number(); })) {
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

}  // namespace

std::optional<sim::Value> valueFromJson(const rt::Program& program, const rt::ValueType& type,
                                        const nlohmann::json& json, std::string& error) {
  std::optional<sim::Value> value = shapeOf(json);
  if (!value) {
    error = fmt::format("expected {}", repl::describeType(program, type));
    return std::nullopt;
  }
  if (!repl::coerceTo(program, type, *value, error)) return std::nullopt;
  return value;
}

std::string jsonPointer(const std::string& key) {
  std::string escaped;
  for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return "/" + escaped;
}

nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
  std::string text;
  try {
    text = support::readInputFile(path, support::kMaxDataBytes, what);
  } catch (const support::InputFileError& e) {
    throw std::runtime_error(e.what());
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: not JSON (at byte {})", path, e.byte));
  }
}

}  // namespace cbtl::app
