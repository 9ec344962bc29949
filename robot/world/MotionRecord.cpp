#include "robot/world/MotionRecord.h"

#include "robot/world/Scene.h"

#include <fmt/core.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace cbtl::world {

namespace {

using json = nlohmann::json;

json poseJson(const Pose3& p) {
  return json::array({p.position.x(), p.position.y(), p.position.z(), p.orientation.w(), p.orientation.x(),
                      p.orientation.y(), p.orientation.z()});
}

Pose3 poseFrom(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 7) throw MotionRecordError(what + " must be [x, y, z, qw, qx, qy, qz]");
  Pose3 p;
  p.position = Eigen::Vector3d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  p.orientation = Eigen::Quaterniond(j[3].get<double>(), j[4].get<double>(), j[5].get<double>(), j[6].get<double>());
  return p;
}

ArmConfig armFrom(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != static_cast<std::size_t>(kArmDof))
    throw MotionRecordError(what + " must hold 7 angles");
  ArmConfig q{};
  for (int i = 0; i < kArmDof; ++i) q[i] = j[static_cast<std::size_t>(i)].get<double>();
  return q;
}

Pose2 baseFrom(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw MotionRecordError(what + " must be [x, y, yaw]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

std::string motionToJson(const Scene& scene, const ExecutedMotion& m) {
  const WorldState& s = m.start;
  json start;
  start["arm"] = s.arm;
  start["base"] = json::array({s.base.x, s.base.y, s.base.yaw});
  start["gripper"] = s.gripper;
  json objects = json::object(), fixtures = json::object();
  for (const auto& [name, pose] : s.objects) objects[name] = poseJson(pose);
  for (const auto& [name, pose] : s.fixtures) fixtures[name] = poseJson(pose);
  start["objects"] = objects;
  start["fixtures"] = fixtures;
  if (s.held) {
    start["held"] = s.held->object;
    start["grasp"] = poseJson(s.held->toolToObject);
  }
  json path = json::array();
  if (m.kind == ExecutedMotion::Kind::Arm) {
    for (const ArmConfig& q : m.arm) path.push_back(q);
  } else {
    for (const Pose2& b : m.base) path.push_back(json::array({b.x, b.y, b.yaw}));
  }
  json allow = json::array();
  for (const ContactAllowance& a : m.allowances) {
    json e{{"part", toString(a.part)}, {"separation", a.separation}};
    if (a.geom >= 0) e["geom"] = scene.geomName(a.geom);
    if (a.body >= 0) e["body"] = scene.bodyName(a.body);
    allow.push_back(e);
  }
  json doc{{"kind", m.kind == ExecutedMotion::Kind::Arm ? "arm" : "base"},
           {"start", start},
           {"path", path},
           {"allow", allow}};
  return doc.dump();
}

ExecutedMotion motionFromJson(const Scene& scene, const std::string& text) {
  ExecutedMotion m;
  try {
    const json doc = json::parse(text);
    const std::string kind = doc.at("kind").get<std::string>();
    if (kind != "arm" && kind != "base") throw MotionRecordError("'kind' must be \"arm\" or \"base\"");
    m.kind = kind == "arm" ? ExecutedMotion::Kind::Arm : ExecutedMotion::Kind::Base;
    const json& st = doc.at("start");
    m.start.arm = armFrom(st.at("arm"), "start.arm");
    m.start.base = baseFrom(st.at("base"), "start.base");
    m.start.gripper = st.at("gripper").get<double>();
    for (const auto& [name, pose] : st.at("objects").items()) {
      if (scene.objectIndex(name) < 0) throw MotionRecordError("the scene has no movable object '" + name + "'");
      m.start.objects[name] = poseFrom(pose, "start.objects." + name);
    }
    for (const auto& [name, pose] : st.at("fixtures").items()) {
      if (scene.fixtureIndex(name) < 0) throw MotionRecordError("the scene has no fixture '" + name + "'");
      m.start.fixtures[name] = poseFrom(pose, "start.fixtures." + name);
    }
    if (st.contains("held")) {
      const std::string held = st.at("held").get<std::string>();
      if (scene.objectIndex(held) < 0) throw MotionRecordError("the scene has no movable object '" + held + "'");
      m.start.held = Grasp{held, poseFrom(st.at("grasp"), "start.grasp")};
    }
    for (const json& w : doc.at("path")) {
      if (m.kind == ExecutedMotion::Kind::Arm)
        m.arm.push_back(armFrom(w, "a path waypoint"));
      else
        m.base.push_back(baseFrom(w, "a path waypoint"));
    }
    if (m.arm.empty() && m.base.empty()) throw MotionRecordError("the path is empty");
    for (const json& a : doc.at("allow")) {
      ContactAllowance c;
      const std::string part = a.at("part").get<std::string>();
      if (part == "held")
        c.part = ContactAllowance::Part::HeldObject;
      else if (part == "gripper")
        c.part = ContactAllowance::Part::Gripper;
      else if (part == "robot")
        c.part = ContactAllowance::Part::Robot;
      else
        throw MotionRecordError("an allowance's part must be held, gripper or robot");
      if (a.contains("geom") && (c.geom = scene.geomId(a.at("geom").get<std::string>())) < 0)
        throw MotionRecordError("an allowance names a geom the scene does not have");
      if (a.contains("body") && (c.body = scene.bodyId(a.at("body").get<std::string>())) < 0)
        throw MotionRecordError("an allowance names a body the scene does not have");
      // Records written before skills could declare clearance exceptions give a contact depth instead.
      c.separation = a.contains("separation") ? a.at("separation").get<double>() : -a.at("depth").get<double>();
      if (!std::isfinite(c.separation)) throw MotionRecordError("an allowance's separation must be a finite number");
      m.allowances.push_back(c);
    }
  } catch (const json::exception& e) {
    throw MotionRecordError(fmt::format("not a motion record: {}", e.what()));
  }
  return m;
}

}  // namespace cbtl::world
