#include "robot/bind/WorldHost.h"

#include "robot/world/MotionQuery.h"
#include "robot/world/NamedConfigurations.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace cbtl::bind {

using world::ArmConfig;
using world::Pose2;
using world::Pose3;

namespace {

constexpr std::size_t kStageCacheSize = 512;
constexpr std::size_t kVerdictCacheSize = 8192;

void appendText(std::vector<double>& k, const std::string& t) {
  k.push_back(static_cast<double>(t.size()));
  for (unsigned char c : t) k.push_back(c);
}

void appendNamedPose(std::vector<double>& k, const std::string& name, const world::Pose3& p) {
  appendText(k, name);
  k.insert(k.end(), {p.position.x(), p.position.y(), p.position.z(), p.orientation.w(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z()});
}

// Every value of a WorldState in a fixed order (objects and fixtures by name: the maps' order).
std::uint64_t stateFingerprint(const world::WorldState& s) {
  std::vector<double> k(s.arm.begin(), s.arm.end());
  k.insert(k.end(), {s.base.x, s.base.y, s.base.yaw, s.gripper});
  for (const auto& [name, p] : s.objects) appendNamedPose(k, name, p);
  k.push_back(static_cast<double>(s.fixtures.size()));  // where the objects end and the fixtures begin
  for (const auto& [name, p] : s.fixtures) appendNamedPose(k, name, p);
  if (s.held) appendNamedPose(k, s.held->object, s.held->toolToObject);
  return world::fingerprintOf(k);
}

std::uint64_t callsFingerprint(std::uint64_t state, std::uint64_t mode, std::span<const sim::ActionCall> calls) {
  std::vector<double> k{static_cast<double>(state >> 32), static_cast<double>(state & 0xffffffffu),
                        static_cast<double>(mode)};
  for (const sim::ActionCall& c : calls) {
    appendText(k, c.name);
    k.push_back(static_cast<double>(c.args.size()));
    for (const sim::Value& v : c.args) {
      k.push_back(static_cast<double>(v.kind));
      k.push_back(v.number);
      k.push_back(static_cast<double>(v.vector.size()));
      k.insert(k.end(), v.vector.begin(), v.vector.end());
      appendText(k, v.text);
      k.push_back(static_cast<double>(v.members.size()));
      for (const std::string& m : v.members) appendText(k, m);
    }
    k.push_back(static_cast<double>(c.exceptions.size()));
    for (const sim::ClearanceException& e : c.exceptions) {
      appendText(k, e.part);
      k.push_back(static_cast<double>(e.names.size()));
      for (const std::string& n : e.names) appendText(k, n);
      k.push_back(e.separation);
    }
  }
  return world::fingerprintOf(k);
}

template <class Map, class Value>
void remember(Map& map, std::deque<std::uint64_t>& order, std::size_t capacity, std::uint64_t key, Value value) {
  if (map.insert_or_assign(key, std::move(value)).second) order.push_back(key);
  while (map.size() > capacity && !order.empty()) {
    map.erase(order.front());
    order.pop_front();
  }
}

}  // namespace

WorldHost::WorldHost(std::shared_ptr<const world::Scene> scene)
    : world_(scene), dryWorld_(scene), executor_(std::make_shared<actions::RobotActions>()) {
  reference_ = world_.workspace().state();
  reference_.arm = world::configs::kRetract;
  world_.workspace().setState(reference_);
  observed_ = reference_;
  observedFingerprint_ = stateFingerprint(observed_);
  dirty_ = false;
}

bool WorldHost::setReference(const world::WorldState& state) {
  if (world_.workspace().setState(state) != world::StateStatus::Ok) {
    dirty_ = true;
    return false;
  }
  reference_ = world_.workspace().state();
  observed_ = reference_;
  observedFingerprint_ = stateFingerprint(observed_);
  stage_ = 0;
  dirty_ = false;
  return true;
}

void WorldHost::useReference(const world::WorldState& state) {
  reference_ = state;
  dirty_ = true;
}

sim::PlanVerdict WorldHost::runCalls(std::span<const sim::ActionCall> calls, actions::ExecutionMode mode) {
  world::Workspace& ws = dryWorld_.workspace();
  ws.setState(observed_);
  sim::PlanVerdict v;
  for (std::size_t i = 0; i < calls.size() && v.executes; ++i) {
    const auto r = executor_->execute(dryWorld_, calls[i], mode);
    if (!r) {
      v = {false, i, calls[i].name, "no world model of this action", ""};
    } else if (!r->done()) {
      v = {false, i, calls[i].name, r->wellFormed ? world::builtins::toString(r->status) : "ill-formed call",
           r->detail};
    }
  }
  dryWorld_.utterances().clear();
  return v;
}

sim::PlanVerdict WorldHost::enterStage(std::span<const sim::ActionCall> prefix) {
  if (prefix.empty()) {
    if (stage_ != 0) useReference(observed_);
    stage_ = 0;
    return {};
  }
  const std::uint64_t key = callsFingerprint(observedFingerprint_, 1, prefix);
  if (key == stage_) return stages_.count(key) ? stages_.at(key).verdict : sim::PlanVerdict{};
  stage_ = key;
  auto it = stages_.find(key);
  if (it == stages_.end()) {
    StageEntry e;
    e.verdict = runCalls(prefix, actions::ExecutionMode::Effects);
    e.state = e.verdict.executes ? dryWorld_.workspace().state() : observed_;
    remember(stages_, stageOrder_, kStageCacheSize, key, std::move(e));
    it = stages_.find(key);
  }
  useReference(it->second.state);
  return it->second.verdict;
}

sim::PlanVerdict WorldHost::dryRun(std::span<const sim::ActionCall> calls, int motionIterations) {
  motionIterations = std::max(motionIterations, 0);
  const std::uint64_t key =
      callsFingerprint(observedFingerprint_, 2 + static_cast<std::uint64_t>(motionIterations), calls);
  if (const auto it = verdicts_.find(key); it != verdicts_.end()) return it->second;
  dryWorld_.planning.maxIterations = motionIterations;
  sim::PlanVerdict v = runCalls(calls, actions::ExecutionMode::Execute);
  remember(verdicts_, verdictOrder_, kVerdictCacheSize, key, v);
  return v;
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
  if (const int site = s.siteId(object + "_tool"); site >= 0) {
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
  // In the object's frame: a quarter turn about x puts the tool z along the object's +y (tool x = object x,
  // tool y = object -z); yaw + pi/2 about the object's z then turns the approach.
  const Eigen::Quaterniond inBody = Eigen::AngleAxisd(yaw + M_PI / 2, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d approach = inBody * Eigen::Vector3d::UnitZ();
  const Pose3 toolInBody{box->center - kSideGraspDepth * approach, inBody};
  return objectPose * toolInBody;
}

std::optional<ArmConfig> WorldHost::namedConf(const std::string& name) const {
  return world::namedConfiguration(scene(), name);
}

std::optional<world::SurfaceFace> WorldHost::surfaceTop(const std::string& geom) const {
  // The face as the workspace shows it: fixtures (Scene.h) stand where the last state put them.
  return world::surfaceFace(world_.workspace(), geom);
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
  if (it != reference_.objects.end())
    p = it->second;
  else
    p = world_.workspace().objectPose(object);
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
    if (std::abs(fp->centerX - top->center.x()) > top->halfX || std::abs(fp->centerY - top->center.y()) > top->halfY)
      continue;
    return name;
  }
  return {};
}

}  // namespace cbtl::bind
