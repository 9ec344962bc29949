#include "WorldHost.h"

#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>

namespace cbtl::bind {

using world::ArmConfig;
using world::Pose2;
using world::Pose3;

WorldHost::WorldHost(std::shared_ptr<const world::Scene> scene) : world_(std::move(scene)) {
  reference_ = world_.workspace().state();
  reference_.arm = world::configs::kRetract;
  world_.workspace().setState(reference_);
  dirty_ = false;
}

bool WorldHost::setReference(const world::WorldState& state) {
  if (world_.workspace().setState(state) != world::StateStatus::Ok) {
    dirty_ = true;
    return false;
  }
  reference_ = world_.workspace().state();
  dirty_ = false;
  return true;
}

bool WorldHost::pose(const Pose2& base, const ArmConfig& q, const std::string* held) {
  world::Workspace& ws = world_.workspace();
  for (double v : q)
    if (!std::isfinite(v)) return false;
  if (!ws.scene().withinLimits(q)) return false;
  const bool swapGrasp = held != nullptr && !held->empty() && (!reference_.held || reference_.held->object != *held);
  if (swapGrasp) {
    const auto grasp = nominalGrasp(*held);
    if (!grasp) return false;
    world::WorldState s = reference_;
    s.arm = q;
    s.base = base;
    s.held = world::Grasp{*held, *grasp};
    if (ws.setState(s) != world::StateStatus::Ok) return false;
    dirty_ = true;
    return true;
  }
  if (dirty_) {
    world::WorldState s = reference_;
    s.arm = q;
    s.base = base;
    if (ws.setState(s) != world::StateStatus::Ok) return false;
    dirty_ = false;
    return true;
  }
  ws.setBase(base);
  ws.setArm(q);
  return true;
}

bool WorldHost::moveObject(const std::string& object, const Pose3& pose) {
  if (world_.workspace().scene().objectIndex(object) < 0) return false;
  dirty_ = true;
  return world_.workspace().setObjectPose(object, pose) == world::StateStatus::Ok;
}

std::optional<Pose3> WorldHost::nominalGrasp(const std::string& object) {
  if (reference_.held && reference_.held->object == object) return reference_.held->toolToObject;
  const world::Scene& s = scene();
  if (s.objectIndex(object) < 0) return std::nullopt;
  const auto objectPose = [&]() -> std::optional<Pose3> {
    auto it = reference_.objects.find(object);
    if (it != reference_.objects.end()) return it->second;
    return world_.workspace().objectPose(object);
  }();
  if (!objectPose) return std::nullopt;
  if (const int site = s.siteId(object + "_grasp"); site >= 0) {
    if (dirty_) pose(reference_.base, reference_.arm);
    const Pose3 tool = world_.workspace().sitePose(site);
    return tool.inverse() * *objectPose;
  }
  const auto tool = sideGrasp(object, *objectPose, -M_PI / 2);
  if (!tool) return std::nullopt;
  return tool->inverse() * *objectPose;
}

std::optional<Pose3> WorldHost::sideGrasp(const std::string& object, const Pose3& objectPose, double yaw) {
  const auto box = world_.clearance().objectBox(object);
  if (!box) return std::nullopt;
  const Eigen::Matrix3d r = objectPose.orientation.toRotationMatrix();
  const Eigen::Vector3d up = r.col(2);
  const Eigen::Vector3d approach = r * (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * -Eigen::Vector3d::UnitX());
  Eigen::Matrix3d tool;
  tool.col(0) = up;
  tool.col(2) = approach;
  tool.col(1) = approach.cross(up);
  Pose3 p;
  p.position = objectPose.transformPoint(box->center);
  p.orientation = Eigen::Quaterniond(tool).normalized();
  return p;
}

std::optional<ArmConfig> WorldHost::namedConf(const std::string& name) const {
  const mjModel* m = world_.workspace().model();
  const int id = mj_name2id(m, mjOBJ_NUMERIC, ("conf_" + name).c_str());
  if (id >= 0 && m->numeric_size[id] == world::kArmDof) {
    ArmConfig q{};
    for (int i = 0; i < world::kArmDof; ++i) q[i] = m->numeric_data[m->numeric_adr[id] + i];
    return q;
  }
  namespace c = world::configs;
  static const std::map<std::string, ArmConfig> table = {
      {"zero", c::kZero}, {"home", c::kHome}, {"retract", c::kRetract}, {"abovePlate", c::kAbovePlate},
      {"utensilAboveMount", c::kUtensilAboveMount}, {"drinkGaze", c::kDrinkGaze}};
  auto it = table.find(name);
  if (it == table.end()) return std::nullopt;
  return it->second;
}

std::optional<SurfaceTop> WorldHost::surfaceTop(const std::string& geom) const {
  const world::Workspace& ws = world_.workspace();
  const int g = ws.scene().geomId(geom);
  if (g < 0 || ws.model()->geom_type[g] != mjGEOM_BOX) return std::nullopt;
  // Scenery never moves, so the geom's frame is the same in every state.
  const mjtNum* s = ws.model()->geom_size + 3 * g;
  const mjtNum* r = ws.data()->geom_xmat + 9 * g;
  const mjtNum* p = ws.data()->geom_xpos + 3 * g;
  double h[3];
  for (int row = 0; row < 3; ++row)
    h[row] = std::abs(r[3 * row]) * s[0] + std::abs(r[3 * row + 1]) * s[1] + std::abs(r[3 * row + 2]) * s[2];
  return SurfaceTop{Eigen::Vector3d(p[0], p[1], p[2] + h[2]), h[0], h[1]};
}

std::optional<WorldHost::Footprint> WorldHost::footprint(const std::string& object, const Pose3& pose) const {
  const auto box = world_.clearance().objectBox(object);
  if (!box) return std::nullopt;
  const Eigen::Matrix3d r = pose.orientation.toRotationMatrix();
  const Eigen::Vector3d c = pose.transformPoint(box->center);
  double h[3];
  for (int row = 0; row < 3; ++row)
    h[row] = std::abs(r(row, 0)) * box->halfExtents.x() + std::abs(r(row, 1)) * box->halfExtents.y() +
             std::abs(r(row, 2)) * box->halfExtents.z();
  return Footprint{c.z() - h[2], c.x(), c.y(), h[0], h[1]};
}

std::string WorldHost::supportSurface(const std::string& object) {
  auto it = reference_.objects.find(object);
  std::optional<Pose3> p;
  if (it != reference_.objects.end()) p = it->second;
  else p = world_.workspace().objectPose(object);
  if (!p) return {};
  const auto fp = footprint(object, *p);
  if (!fp) return {};
  const mjModel* m = world_.workspace().model();
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_BOX) continue;
    if (scene().bodyKind(m->geom_bodyid[g]) != world::BodyKind::Scenery) continue;
    const std::string name = scene().geomName(g);
    if (name.empty()) continue;
    const auto top = surfaceTop(name);
    if (!top) continue;
    if (std::abs(fp->bottom - top->center.z()) > 0.01) continue;
    if (std::abs(fp->centerX - top->center.x()) > top->halfX || std::abs(fp->centerY - top->center.y()) > top->halfY) continue;
    return name;
  }
  return {};
}

}  // namespace cbtl::bind
