#include "robot/world/Workspace.h"

#include "robot/world/MujocoErrors.h"

#include <algorithm>
#include <cmath>

namespace cbtl::world {

const char* toString(StateStatus s) {
  switch (s) {
    case StateStatus::Ok:
      return "ok";
    case StateStatus::UnknownObject:
      return "unknown object";
    case StateStatus::OutOfLimits:
      return "arm joint out of limits";
  }
  return "unknown";
}

namespace {

// A pose as MuJoCo stores it: position (x y z) and unit quaternion (w x y z).
void writePose(const Pose3& pose, mjtNum* position, mjtNum* quaternion) {
  const Eigen::Quaterniond o = pose.orientation.normalized();
  position[0] = pose.position.x();
  position[1] = pose.position.y();
  position[2] = pose.position.z();
  quaternion[0] = o.w();
  quaternion[1] = o.x();
  quaternion[2] = o.y();
  quaternion[3] = o.z();
}

}  // namespace

Workspace::Workspace(std::shared_ptr<const Scene> scene) : scene_(std::move(scene)) {
  installMujocoHandlers();
  data_ = mj_makeData(scene_->model());
  // Start from the model's reference pose (qpos0): objects where the XML put them, arm at zero.
  mj_resetData(scene_->model(), data_);
  for (int i = 0; i < kArmDof; ++i) state_.arm[i] = data_->qpos[scene_->armQposAdr(i)];
  for (const auto& obj : scene_->objects()) {
    const mjtNum* q = data_->qpos + obj.qposAdr;
    state_.objects[obj.name] = Pose3{Eigen::Vector3d(q[0], q[1], q[2]), Eigen::Quaterniond(q[3], q[4], q[5], q[6])};
  }
  for (const auto& f : scene_->fixtures()) {
    const mjtNum* p = data_->mocap_pos + 3 * f.mocapId;
    const mjtNum* q = data_->mocap_quat + 4 * f.mocapId;
    state_.fixtures[f.name] = Pose3{Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Quaterniond(q[0], q[1], q[2], q[3])};
  }
  recompute();
}

Workspace::~Workspace() { mj_deleteData(data_); }

StateStatus Workspace::setState(const WorldState& state) {
  const Scene& s = *scene_;
  for (double v : state.arm)
    if (!std::isfinite(v)) return StateStatus::OutOfLimits;
  if (!s.withinLimits(state.arm)) return StateStatus::OutOfLimits;
  for (const auto& [name, pose] : state.objects)
    if (s.objectIndex(name) < 0) return StateStatus::UnknownObject;
  for (const auto& [name, pose] : state.fixtures)
    if (s.fixtureIndex(name) < 0) return StateStatus::UnknownObject;
  if (state.held && s.objectIndex(state.held->object) < 0) return StateStatus::UnknownObject;

  const std::map<std::string, Pose3> previous = state_.objects;
  const std::map<std::string, Pose3> previousFixtures = state_.fixtures;
  state_ = state;
  for (const auto& [name, pose] : previous) state_.objects.try_emplace(name, pose);
  for (const auto& [name, pose] : previousFixtures) state_.fixtures.try_emplace(name, pose);
  heldIndex_ = state.held ? s.objectIndex(state.held->object) : -1;
  for (int i = 0; i < kArmDof; ++i) data_->qpos[s.armQposAdr(i)] = state.arm[i];
  if (s.hasMobileBase()) {
    data_->qpos[s.baseQposAdr(0)] = state.base.x;
    data_->qpos[s.baseQposAdr(1)] = state.base.y;
    data_->qpos[s.baseQposAdr(2)] = state.base.yaw;
  }
  const double closed = std::clamp(1.0 - state.gripper, 0.0, 1.0) * s.fingerTravel();
  for (int i = 0; i < 2; ++i)
    if (s.fingerQposAdr(i) >= 0) data_->qpos[s.fingerQposAdr(i)] = closed;
  for (size_t i = 0; i < s.objects().size(); ++i)
    writeObject(static_cast<int>(i), state_.objects.at(s.objects()[i].name));
  for (size_t i = 0; i < s.fixtures().size(); ++i)
    writeFixture(static_cast<int>(i), state_.fixtures.at(s.fixtures()[i].name));
  recompute();
  return StateStatus::Ok;
}

void Workspace::setArm(const ArmConfig& q) {
  state_.arm = q;
  for (int i = 0; i < kArmDof; ++i) data_->qpos[scene_->armQposAdr(i)] = q[i];
  recompute(scene_->armSubtree());
}

void Workspace::setBase(const Pose2& base) {
  state_.base = base;
  if (scene_->hasMobileBase()) {
    data_->qpos[scene_->baseQposAdr(0)] = base.x;
    data_->qpos[scene_->baseQposAdr(1)] = base.y;
    data_->qpos[scene_->baseQposAdr(2)] = base.yaw;
  }
  recompute(scene_->baseSubtree());
}

StateStatus Workspace::setHeld(const std::optional<std::string>& object) {
  if (!object) {
    state_.held.reset();
    heldIndex_ = -1;
    return StateStatus::Ok;
  }
  const int idx = scene_->objectIndex(*object);
  if (idx < 0) return StateStatus::UnknownObject;
  const Pose3 rel = toolPose().inverse() * bodyPose(scene_->objects()[idx].body);
  state_.held = Grasp{*object, rel};
  heldIndex_ = idx;
  recompute();
  return StateStatus::Ok;
}

StateStatus Workspace::setObjectPose(std::string_view object, const Pose3& pose) {
  const int idx = scene_->objectIndex(object);
  if (idx < 0) return StateStatus::UnknownObject;
  if (idx == heldIndex_) return StateStatus::Ok;
  state_.objects[std::string(object)] = pose;
  writeObject(idx, pose);
  recompute(scene_->objectSubtree(idx));
  return StateStatus::Ok;
}

StateStatus Workspace::setFixturePose(std::string_view fixture, const Pose3& pose) {
  const int idx = scene_->fixtureIndex(fixture);
  if (idx < 0) return StateStatus::UnknownObject;
  state_.fixtures[std::string(fixture)] = pose;
  writeFixture(idx, pose);
  recompute();
  return StateStatus::Ok;
}

void Workspace::writeFixture(int index, const Pose3& pose) {
  const int id = scene_->fixtures()[static_cast<size_t>(index)].mocapId;
  writePose(pose, data_->mocap_pos + 3 * id, data_->mocap_quat + 4 * id);
}

void Workspace::writeObject(int index, const Pose3& pose) {
  mjtNum* q = data_->qpos + scene_->objects()[static_cast<size_t>(index)].qposAdr;
  writePose(pose, q, q + 3);  // a free joint's qpos: x y z, then qw qx qy qz
}

void Workspace::recompute(const KinematicSubtree& moved) {
  auto update = [this](const KinematicSubtree& tree) {
    if (tree.supported())
      tree.update(scene_->model(), data_);
    else
      mj_kinematics(scene_->model(), data_);
  };
  update(moved);
  if (heldIndex_ >= 0 && state_.held) {
    const Pose3 pose = toolPose() * state_.held->toolToObject;
    writeObject(heldIndex_, pose);
    state_.objects[state_.held->object] = pose;
    update(scene_->objectSubtree(heldIndex_));
  }
}

Pose3 Workspace::sitePose(int site) const {
  const mjtNum* p = data_->site_xpos + 3 * site;
  const mjtNum* r = data_->site_xmat + 9 * site;
  Eigen::Matrix3d rot;
  rot << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  return {Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Quaterniond(rot).normalized()};
}

std::optional<Pose3> Workspace::sitePose(std::string_view site) const {
  const int id = scene_->siteId(site);
  if (id < 0) return std::nullopt;
  return sitePose(id);
}

Pose3 Workspace::bodyPose(int body) const {
  const mjtNum* p = data_->xpos + 3 * body;
  const mjtNum* q = data_->xquat + 4 * body;
  return {Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized()};
}

std::optional<Pose3> Workspace::objectPose(std::string_view object) const {
  const int idx = scene_->objectIndex(object);
  if (idx < 0) return std::nullopt;
  return bodyPose(scene_->objects()[static_cast<size_t>(idx)].body);
}

Pose3 Workspace::forwardKinematics(const ArmConfig& q) {
  setArm(q);
  return toolPose();
}

}  // namespace cbtl::world
