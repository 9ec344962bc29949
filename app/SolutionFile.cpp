#include "app/SolutionFile.h"

#include "app/JsonValues.h"
#include "runtime/approach/ValueBridge.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace cbtl::app {

namespace {

// Writes `json` (a value of `type`) at `out`, or throws naming where it is in the file.
void readValue(const std::string& path, const std::string& where, const rt::Program& program, const rt::ValueType& type,
               const nlohmann::json& json, double* out) {
  std::string error;
  const std::optional<sim::Value> value = valueFromJson(program, type, json, error);
  if (!value || !approach::fromSimValue(program, type, *value, out, error))
    throw SolutionFileError(fmt::format("{}: {}: {}", path, where, error));
}

const nlohmann::json& member(const std::string& path, const nlohmann::json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) throw SolutionFileError(fmt::format("{}: no \"{}\" (not a cbtl-solution?)", path, key));
  return *it;
}

}  // namespace

SolutionMoment readSolutionFile(const std::string& path, const rt::Program& program) {
  SolutionMoment moment;
  nlohmann::json root;
  try {
    root = readJsonFile(path, "solution file");
  } catch (const std::runtime_error& e) {
    throw SolutionFileError(e.what());
  }
  if (!root.is_object() || root.value("format", "") != "cbtl-solution")
    throw SolutionFileError(fmt::format("{}: not a cbtl-solution (cbtl solve --format json writes one)", path));
  if (root.value("version", 0) != 1)
    throw SolutionFileError(fmt::format("{}: /version: only version 1 is known", path));
  const nlohmann::json& status = member(path, root, "status");
  if (status != "solved")
    throw SolutionFileError(
        fmt::format("{}: /status: the solve it records found no solution ({}); feedback is "
                    "about a solution",
                    path, status.dump()));
  const nlohmann::json& task = member(path, root, "task");
  const ir::Task* t = task.is_string() ? program.findTask(task.get<std::string>()) : nullptr;
  if (t == nullptr) throw SolutionFileError(fmt::format("{}: /task: the program has no task {}", path, task.dump()));
  moment.task = t->name;

  const nlohmann::json& observed = member(path, root, "observation");
  if (!observed.is_object()) throw SolutionFileError(fmt::format("{}: /observation: expected an object", path));
  moment.observation.assign(program.observationWidth(), 0.0);
  for (const auto& [name, slot] : program.observationSlots()) {
    const auto it = observed.find(name);
    if (it == observed.end()) throw SolutionFileError(fmt::format("{}: /observation: no value for '{}'", path, name));
    readValue(path, "/observation" + jsonPointer(name), program, slot.type, *it,
              moment.observation.data() + slot.offset);
  }

  const nlohmann::json& assignment = member(path, root, "assignment");
  if (!assignment.is_object()) throw SolutionFileError(fmt::format("{}: /assignment: expected an object", path));
  moment.assignment = program.initialAssignment(moment.observation);
  for (ir::VarId v : t->vars) {
    const std::string& name = program.graph().variables[v].name;
    const auto it = assignment.find(name);
    if (it == assignment.end())
      throw SolutionFileError(
          fmt::format("{}: /assignment: no value for '{}' (a variable of task {})", path, name, t->name));
    const auto& slot = program.slot(v);
    readValue(path, "/assignment" + jsonPointer(name), program, slot.type, *it, moment.assignment.data() + slot.offset);
  }
  moment.text = root.dump();
  return moment;
}

}  // namespace cbtl::app
