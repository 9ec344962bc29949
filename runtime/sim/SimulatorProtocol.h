// SimulatorProtocol.h — the messages of the external simulator protocol, version 1 (docs/simulator-protocol.md is
// the reference for people who write simulators; keep both in step).
//
// cbtl writes one JSON object per line on the simulator's stdin and reads exactly one JSON object per line back
// on its stdout, answer for request, in order. Every request carries "id" (1, 2, ...) and "op"; every answer
// repeats the id and says "ok": true, or "ok": false with an "error" text. Requests:
//   hello   {"protocol": 1, "domain", "options"}  -> the manifest: "protocol", "observations", "actions",
//           "feedback", "tasks" (names), optional "preferences" (the outcome's judged preferences, in order) and
//           "simulator" (a name for messages). World 0, the training world, exists from then on.
//   reset   {"world", "seed"}                      -> {"task"?}   a new episode drawn with the seed
//   observe {"world"}                              -> {"observation": {...}} (ProtocolSchema.h's encoding)
//   act     {"world", "action", "args": {...}}     -> a step result (below)
//   idle    {"world"}                              -> a step result
//   twin    {"world"}                              -> {"world": W} a new world with its own state and random
//           numbers that shares the simulated user with "world" (the evaluation world)
//   close   {"world"}                              -> {}  the world is not used again
//   bye     {}                                     -> {}  then stdin closes; the program should exit
// A step result: "status" ("applied" | "ignored" | "unknown": the simulator has no such action), "step" (the
// clock advanced), "done", "failed", "satisfaction" (present when the user scored this step), "feedback" (a list
// of {"event", "args"}), "preferences" ({name: met}), "measures" ({name: number}), "preferences_changed",
// "caregiver_reset", "message", "task" (the task the world asks for now; absent or "": the configured one).
// Every field is optional; an answer with a field the protocol does not define is refused (a typo would
// otherwise be lost).
#pragma once

#include "runtime/sim/DomainSimulator.h"
#include "runtime/sim/ProtocolSchema.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace cbtl::sim::protocol {

inline constexpr int kVersion = 1;

// The options of a hello request.
nlohmann::json optionsJson(const SimulatorOptions& options);
SimulatorOptions optionsFrom(const nlohmann::json& options);

// A step result as an answer's fields (without "id" and "ok").
nlohmann::json encodeStep(const ProtocolSchema& schema, const StepResult& step, const std::string& requestedTask);

// An answer read as a step result, every value checked against the schema; throws std::runtime_error saying
// which field is wrong. `requestedTask` receives "task" (empty when absent).
StepResult decodeStep(const ProtocolSchema& schema, const nlohmann::json& answer, std::string& requestedTask);

// The "task" field of a reset or step answer: empty when absent or null; throws std::runtime_error when it is not
// a string or names no task of the program.
std::string requestedTaskOf(const ProtocolSchema& schema, const nlohmann::json& answer);

// What a hello answer's manifest does not agree with in the program: every error at once (an empty list: it
// fits), and warnings that do not stop a run (an event a `learn` rule reads that the simulator never sends).
struct ManifestCheck {
  std::vector<std::string> errors, warnings;
  std::vector<std::string> preferences;  // "preferences", in order
  std::string simulatorName;
};
ManifestCheck checkManifest(const ProtocolSchema& schema, const nlohmann::json& hello);

// The manifest of a simulator that serves the whole program (cbtl simulator serve): every observation, action,
// event and task of the schema, and `preferences`.
nlohmann::json manifestFor(const ProtocolSchema& schema, const std::vector<std::string>& preferences,
                           const std::string& simulatorName);

}  // namespace cbtl::sim::protocol
