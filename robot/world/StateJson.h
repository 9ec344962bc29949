// StateJson.h — world states written as small JSON documents (used by `cbtl render --state`).
//
//   {
//     "arm": [q1, ..., q7] | "zero" | "home" | "retract",      // radians
//     "base": {"x": 0.0, "y": 0.0, "yaw": 0.0},               // m, m, rad (mobile-base scenes)
//     "gripper": 1.0,                                         // opening in [0, 1]
//     "objects": {"plate": {"position": [x, y, z], "quaternion": [w, x, y, z]},
//                 "drink": {"position": [x, y, z], "yaw": 0.5}},
//     "fixtures": {"table_round": {"position": [x, y, z]}},      // mocap bodies (Scene.h)
//     "held": "utensil"                                       // attach at its pose relative to the tool
//   }
// Every field is optional; missing ones keep the Workspace's current values. Unknown top-level keys are
// errors, so typos do not pass silently. Frames: world; units: metres and radians.
#pragma once

#include "robot/world/Workspace.h"

#include <string>

namespace cbtl::world {

enum class StateJsonStatus {
  Ok,
  FileNotFound,
  BadJson,   // not valid JSON
  BadValue,  // valid JSON with a wrong field, type, object name or joint value
};

struct StateJsonResult {
  StateJsonStatus status = StateJsonStatus::Ok;
  std::string message;  // names the file (or "<string>") and the offending field when not Ok
};

// Parses `text` and applies it to `ws`; on failure `ws` is unchanged.
StateJsonResult applyStateJson(Workspace& ws, const std::string& text, const std::string& sourceName = "<string>");
StateJsonResult applyStateFile(Workspace& ws, const std::string& path);

}  // namespace cbtl::world
