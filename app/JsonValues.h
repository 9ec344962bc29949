// JsonValues.h — a JSON value read as a value of a declared type: the inverse of what `cbtl solve --format json`
// writes (app/SolutionJson.h), shared by the files a person or a program gives the runtime (observations,
// solutions). Numbers and true/false are numbers, strings are names (an enum member or item entry, bare or
// qualified) or text, an array of numbers is a vector or pose, an array of strings is a set.
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <vector>

namespace cbtl::app {

// The boundary's value for `json`, checked against `type`; nullopt with a message naming what was expected.
std::optional<sim::Value> valueFromJson(const rt::Program& program, const rt::ValueType& type,
                                        const nlohmann::json& json, std::string& error);

// "/key" with the JSON Pointer escapes (~0, ~1), for messages that point into a file.
std::string jsonPointer(const std::string& key);

// Reads a whole file as JSON; throws std::runtime_error naming the path when it cannot be read or parsed.
nlohmann::json readJsonFile(const std::string& path, const std::string& what);

}  // namespace cbtl::app
