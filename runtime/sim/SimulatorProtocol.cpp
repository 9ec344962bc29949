#include "runtime/sim/SimulatorProtocol.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace cbtl::sim::protocol {

namespace {

using nlohmann::json;

const char* statusName(ActionStatus s) {
  switch (s) {
    case ActionStatus::Applied:
      return "applied";
    case ActionStatus::Ignored:
      return "ignored";
    case ActionStatus::UnknownAction:
      return "unknown";
  }
  return "applied";
}

bool boolField(const json& answer, const char* name) {
  const auto it = answer.find(name);
  if (it == answer.end()) return false;
  if (!it->is_boolean()) throw std::runtime_error(fmt::format("\"{}\" must be true or false", name));
  return it->get<bool>();
}

double numberField(const json& value, const std::string& what) {
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    throw std::runtime_error(fmt::format("{} must be a finite number, got {}", what, value.dump()));
  return value.get<double>();
}

// The names a manifest field lists; throws when it is not an array of strings.
std::vector<std::string> names(const json& hello, const char* field) {
  const auto it = hello.find(field);
  if (it == hello.end()) return {};
  if (!it->is_array()) throw std::runtime_error(fmt::format("the manifest's \"{}\" must be an array of names", field));
  std::vector<std::string> out;
  for (const json& e : *it) {
    if (!e.is_string())
      throw std::runtime_error(
          fmt::format("the manifest's \"{}\" must be an array of names, it holds {}", field, e.dump()));
    out.push_back(e.get<std::string>());
  }
  return out;
}

std::string at(const std::string& where) { return where.empty() ? std::string() : " (" + where + ")"; }

}  // namespace

json optionsJson(const SimulatorOptions& o) {
  return {{"shift_every", o.shiftEvery},
          {"shift_lo", o.shiftLo},
          {"shift_hi", o.shiftHi},
          {"announce_shifts", o.announceShifts},
          {"unsatisfiable_stock_probability", o.unsatisfiableStockProbability},
          {"participant", o.participant}};
}

SimulatorOptions optionsFrom(const json& j) {
  SimulatorOptions o;
  if (!j.is_object()) return o;
  o.shiftEvery = j.value("shift_every", o.shiftEvery);
  o.shiftLo = j.value("shift_lo", o.shiftLo);
  o.shiftHi = j.value("shift_hi", o.shiftHi);
  o.announceShifts = j.value("announce_shifts", o.announceShifts);
  o.unsatisfiableStockProbability = j.value("unsatisfiable_stock_probability", o.unsatisfiableStockProbability);
  o.participant = j.value("participant", o.participant);
  return o;
}

json encodeStep(const ProtocolSchema& schema, const StepResult& r, const std::string& requestedTask) {
  json out = {{"status", statusName(r.status)}, {"step", r.consumedStep}};
  if (r.taskDone) out["done"] = true;
  if (r.taskFailed) out["failed"] = true;
  if (r.hasSatisfaction) out["satisfaction"] = r.satisfaction;
  if (!r.feedback.empty()) {
    json events = json::array();
    for (const FeedbackEvent& e : r.feedback) {
      const auto sig = schema.feedback.find(e.name);
      events.push_back(
          {{"event", e.name},
           {"args", sig == schema.feedback.end() ? json::object() : encodeArguments(sig->second, e.args)}});
    }
    out["feedback"] = std::move(events);
  }
  if (!r.preferences.empty()) {
    out["preferences"] = json::object();
    for (const auto& [name, met] : r.preferences) out["preferences"][name] = met;
  }
  if (!r.measures.empty()) {
    out["measures"] = json::object();
    for (const auto& [name, value] : r.measures) out["measures"][name] = value;
  }
  if (r.preferencesChanged) out["preferences_changed"] = true;
  if (r.caregiverReset) out["caregiver_reset"] = true;
  if (!r.message.empty()) out["message"] = r.message;
  if (!requestedTask.empty()) out["task"] = requestedTask;
  return out;
}

StepResult decodeStep(const ProtocolSchema& schema, const json& answer, std::string& requestedTask) {
  static const std::set<std::string> known = {"id",
                                              "ok",
                                              "status",
                                              "step",
                                              "done",
                                              "failed",
                                              "satisfaction",
                                              "feedback",
                                              "preferences",
                                              "measures",
                                              "preferences_changed",
                                              "caregiver_reset",
                                              "message",
                                              "task"};
  for (const auto& [key, _] : answer.items())
    if (known.count(key) == 0)
      throw std::runtime_error(fmt::format(
          "a step result has no field \"{}\" (its fields: status, step, done, failed, satisfaction, feedback, "
          "preferences, measures, preferences_changed, caregiver_reset, message, task)",
          key));
  StepResult r;
  if (const auto it = answer.find("status"); it != answer.end()) {
    const std::string s = it->is_string() ? it->get<std::string>() : std::string();
    if (s == "applied")
      r.status = ActionStatus::Applied;
    else if (s == "ignored")
      r.status = ActionStatus::Ignored;
    else if (s == "unknown")
      r.status = ActionStatus::UnknownAction;
    else
      throw std::runtime_error(
          fmt::format("\"status\" must be \"applied\", \"ignored\" or \"unknown\", got {}", it->dump()));
  }
  r.consumedStep = boolField(answer, "step");
  r.taskDone = boolField(answer, "done");
  r.taskFailed = boolField(answer, "failed");
  if (r.taskFailed && !r.taskDone) throw std::runtime_error("\"failed\": true needs \"done\": true");
  r.preferencesChanged = boolField(answer, "preferences_changed");
  r.caregiverReset = boolField(answer, "caregiver_reset");
  if (const auto it = answer.find("satisfaction"); it != answer.end() && !it->is_null()) {
    r.hasSatisfaction = true;
    r.satisfaction = numberField(*it, "\"satisfaction\"");
  }
  if (const auto it = answer.find("feedback"); it != answer.end()) {
    if (!it->is_array()) throw std::runtime_error("\"feedback\" must be a list of {\"event\", \"args\"} objects");
    for (const json& e : *it) {
      if (!e.is_object() || !e.contains("event") || !e["event"].is_string())
        throw std::runtime_error(
            fmt::format("a feedback entry must be {{\"event\": NAME, \"args\": ...}}, got {}", e.dump()));
      for (const auto& [key, _] : e.items())
        if (key != "event" && key != "args")
          throw std::runtime_error(fmt::format("a feedback entry has no field \"{}\" (its fields: event, args)", key));
      const std::string name = e["event"].get<std::string>();
      const auto sig = schema.feedback.find(name);
      if (sig == schema.feedback.end())
        throw std::runtime_error(
            fmt::format("feedback event '{}' is not declared by the program (no `feedback {}(...)`)", name, name));
      std::string error;
      auto args = decodeArguments(sig->second, e.contains("args") ? e["args"] : json::object(), error);
      if (!args) throw std::runtime_error(fmt::format("feedback {}", error));
      r.feedback.push_back({name, std::move(*args)});
    }
  }
  if (const auto it = answer.find("preferences"); it != answer.end()) {
    if (!it->is_object()) throw std::runtime_error("\"preferences\" must be an object {name: true|false}");
    for (const auto& [name, met] : it->items()) {
      if (!met.is_boolean())
        throw std::runtime_error(fmt::format("preference '{}' must be true or false, got {}", name, met.dump()));
      r.preferences.emplace_back(name, met.get<bool>());
    }
  }
  if (const auto it = answer.find("measures"); it != answer.end()) {
    if (!it->is_object()) throw std::runtime_error("\"measures\" must be an object {name: number}");
    for (const auto& [name, value] : it->items())
      r.measures.emplace_back(name, numberField(value, fmt::format("measure '{}'", name)));
  }
  if (const auto it = answer.find("message"); it != answer.end()) {
    if (!it->is_string()) throw std::runtime_error("\"message\" must be a string");
    r.message = it->get<std::string>();
  }
  requestedTask = requestedTaskOf(schema, answer);
  return r;
}

std::string requestedTaskOf(const ProtocolSchema& schema, const json& answer) {
  const auto it = answer.find("task");
  if (it == answer.end() || it->is_null()) return {};
  if (!it->is_string()) throw std::runtime_error("\"task\" must be a task's name");
  std::string task = it->get<std::string>();
  if (!task.empty() && std::find(schema.tasks.begin(), schema.tasks.end(), task) == schema.tasks.end())
    throw std::runtime_error(fmt::format("\"task\": the program has no task '{}'", task));
  return task;
}

ManifestCheck checkManifest(const ProtocolSchema& schema, const json& hello) {
  ManifestCheck c;
  static const std::set<std::string> known = {"id",      "ok",       "protocol", "simulator",  "observations",
                                              "actions", "feedback", "tasks",    "preferences"};
  for (const auto& [key, _] : hello.items())
    if (known.count(key) == 0)
      c.errors.push_back(
          fmt::format("the manifest has no field \"{}\" (its fields: protocol, simulator, "
                      "observations, actions, feedback, tasks, preferences)",
                      key));
  const auto version = hello.find("protocol");
  if (version == hello.end() || !version->is_number_integer() || version->get<int>() != kVersion) {
    c.errors.push_back(fmt::format("the simulator speaks protocol {}, cbtl speaks protocol {}",
                                   version == hello.end() ? std::string("(none given)") : version->dump(), kVersion));
    return c;  // the rest may mean something else in another version
  }
  if (const auto it = hello.find("simulator"); it != hello.end() && it->is_string()) c.simulatorName = *it;
  try {
    const auto observations = names(hello, "observations");
    const std::set<std::string> offered(observations.begin(), observations.end());
    for (const auto& [name, where] : schema.observationNames)
      if (offered.count(name) == 0)
        c.errors.push_back(
            fmt::format("the program observes '{}'{}; the simulator does not provide it", name, at(where)));
    for (const auto& name : observations)
      if (schema.observationNames.count(name) == 0)
        c.errors.push_back(
            fmt::format("the simulator provides the observation '{}', which the program does not declare", name));

    const auto actions = names(hello, "actions");
    const std::set<std::string> served(actions.begin(), actions.end());
    for (const auto& [name, sig] : schema.actions)
      if (served.count(name) == 0)
        c.errors.push_back(fmt::format("the program calls the action '{}'{}; the simulator does not perform it", name,
                                       at(sig.declaredAt)));

    const auto events = names(hello, "feedback");
    const std::set<std::string> sent(events.begin(), events.end());
    for (const auto& name : events)
      if (schema.feedback.count(name) == 0)
        c.errors.push_back(
            fmt::format("the simulator sends the feedback event '{}', which the program does not declare", name));
    for (const auto& name : schema.learnedEvents)
      if (sent.count(name) == 0 && schema.feedback.count(name) > 0)
        c.warnings.push_back(
            fmt::format("the program learns from '{}'{}, which the simulator never sends: nothing "
                        "will be learned from it",
                        name, at(schema.feedback.at(name).declaredAt)));

    for (const auto& name : names(hello, "tasks"))
      if (std::find(schema.tasks.begin(), schema.tasks.end(), name) == schema.tasks.end())
        c.errors.push_back(
            fmt::format("the simulator may ask for the task '{}', which the program does not define", name));
    c.preferences = names(hello, "preferences");
  } catch (const std::runtime_error& e) {
    c.errors.push_back(e.what());
  }
  return c;
}

json manifestFor(const ProtocolSchema& schema, const std::vector<std::string>& preferences,
                 const std::string& simulatorName) {
  json observations = json::array(), actions = json::array(), events = json::array();
  for (const auto& [name, _] : schema.observationNames) observations.push_back(name);
  for (const auto& [name, _] : schema.actions) actions.push_back(name);
  for (const auto& [name, _] : schema.feedback) events.push_back(name);
  return {{"protocol", kVersion}, {"simulator", simulatorName}, {"observations", observations}, {"actions", actions},
          {"feedback", events},   {"tasks", schema.tasks},      {"preferences", preferences}};
}

}  // namespace cbtl::sim::protocol
