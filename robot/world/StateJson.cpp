#include "robot/world/StateJson.h"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace cbtl::world {

namespace {

using nlohmann::json;

struct BadValue {
  std::string what;
};

double number(const json& j, const std::string& field) {
  if (!j.is_number()) throw BadValue{fmt::format("'{}' must be a number", field)};
  return j.get<double>();
}

Eigen::Vector3d vec3(const json& j, const std::string& field) {
  if (!j.is_array() || j.size() != 3) throw BadValue{fmt::format("'{}' must be an array of 3 numbers", field)};
  return {number(j[0], field), number(j[1], field), number(j[2], field)};
}

ArmConfig parseArm(const json& j) {
  if (j.is_string()) {
    const auto name = j.get<std::string>();
    if (name == "zero") return configs::kZero;
    if (name == "home") return configs::kHome;
    if (name == "retract") return configs::kRetract;
    throw BadValue{fmt::format("'arm': unknown named configuration '{}' (zero, home, retract)", name)};
  }
  if (!j.is_array() || j.size() != kArmDof) throw BadValue{"'arm' must be an array of 7 joint angles or a name"};
  ArmConfig q{};
  for (int i = 0; i < kArmDof; ++i) q[i] = number(j[static_cast<std::size_t>(i)], "arm");
  return q;
}

Pose3 parsePose(const json& j, const std::string& field) {
  if (!j.is_object()) throw BadValue{fmt::format("'{}' must be an object with a position", field)};
  Pose3 p;
  for (const auto& [key, value] : j.items()) {
    if (key == "position") {
      p.position = vec3(value, field + ".position");
    } else if (key == "quaternion") {
      if (!value.is_array() || value.size() != 4)
        throw BadValue{fmt::format("'{}.quaternion' must be [w, x, y, z]", field)};
      p.orientation = Eigen::Quaterniond(number(value[0], field), number(value[1], field), number(value[2], field),
                                         number(value[3], field));
      if (p.orientation.norm() < 1e-9) throw BadValue{fmt::format("'{}.quaternion' is zero", field)};
      p.orientation.normalize();
    } else if (key == "yaw") {
      p.orientation = Eigen::AngleAxisd(number(value, field + ".yaw"), Eigen::Vector3d::UnitZ());
    } else {
      throw BadValue{fmt::format("'{}': unknown key '{}' (position, quaternion, yaw)", field, key)};
    }
  }
  if (!j.contains("position")) throw BadValue{fmt::format("'{}' needs a position", field)};
  return p;
}

}  // namespace

StateJsonResult applyStateJson(Workspace& ws, const std::string& text, const std::string& sourceName) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    return {StateJsonStatus::BadJson, fmt::format("{}: invalid JSON: {}", sourceName, e.what())};
  }
  WorldState st = ws.state();
  st.held.reset();
  std::optional<std::string> held;
  try {
    if (!doc.is_object()) throw BadValue{"the state must be a JSON object"};
    for (const auto& [key, value] : doc.items()) {
      if (key == "arm") {
        st.arm = parseArm(value);
      } else if (key == "base") {
        if (!value.is_object()) throw BadValue{"'base' must be an object {x, y, yaw}"};
        st.base.x = value.contains("x") ? number(value["x"], "base.x") : 0.0;
        st.base.y = value.contains("y") ? number(value["y"], "base.y") : 0.0;
        st.base.yaw = value.contains("yaw") ? number(value["yaw"], "base.yaw") : 0.0;
      } else if (key == "gripper") {
        st.gripper = number(value, "gripper");
        if (st.gripper < 0 || st.gripper > 1) throw BadValue{"'gripper' must lie in [0, 1]"};
      } else if (key == "objects") {
        if (!value.is_object()) throw BadValue{"'objects' must map object names to poses"};
        for (const auto& [name, pose] : value.items()) {
          if (ws.scene().objectIndex(name) < 0)
            throw BadValue{fmt::format("'objects': the scene has no movable object '{}'", name)};
          st.objects[name] = parsePose(pose, "objects." + name);
        }
      } else if (key == "fixtures") {
        if (!value.is_object()) throw BadValue{"'fixtures' must map fixture names to poses"};
        for (const auto& [name, pose] : value.items()) {
          if (ws.scene().fixtureIndex(name) < 0)
            throw BadValue{fmt::format("'fixtures': the scene has no fixture (mocap body) '{}'", name)};
          st.fixtures[name] = parsePose(pose, "fixtures." + name);
        }
      } else if (key == "held") {
        if (!value.is_string()) throw BadValue{"'held' must be an object name"};
        held = value.get<std::string>();
        if (ws.scene().objectIndex(*held) < 0)
          throw BadValue{fmt::format("'held': the scene has no movable object '{}'", *held)};
      } else {
        throw BadValue{fmt::format("unknown key '{}' (arm, base, gripper, objects, fixtures, held)", key)};
      }
    }
  } catch (const BadValue& e) {
    return {StateJsonStatus::BadValue, fmt::format("{}: {}", sourceName, e.what)};
  }
  const StateStatus s = ws.setState(st);
  if (s != StateStatus::Ok) return {StateJsonStatus::BadValue, fmt::format("{}: {}", sourceName, toString(s))};
  if (held) ws.setHeld(held);
  return {};
}

StateJsonResult applyStateFile(Workspace& ws, const std::string& path) {
  std::ifstream in(path);
  if (!in) return {StateJsonStatus::FileNotFound, fmt::format("{}: state file not found or not readable", path)};
  std::stringstream buf;
  buf << in.rdbuf();
  return applyStateJson(ws, buf.str(), path);
}

}  // namespace cbtl::world
