#include "robot/world/Scene.h"

#include "robot/world/GeomDistance.h"
#include "robot/world/MotionBound.h"
#include "robot/world/MotionQuery.h"
#include "robot/world/MujocoErrors.h"

#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace cbtl::world {

namespace {

SceneLoadResult fail(LoadStatus s, std::string msg) { return {s, std::move(msg), nullptr}; }

// Calls mj_loadXML and converts both of MuJoCo's failure channels (a null model with a message, or a
// thrown MujocoError from the installed handler) into a message.
mjModel* loadXml(const char* path, std::string& error) {
  char err[1024] = {0};
  mjModel* m = nullptr;
  try {
    m = mj_loadXML(path, nullptr, err, sizeof err);
  } catch (const MujocoError& e) {
    error = e.what();
    return nullptr;
  }
  if (!m) error = err[0] ? err : "MuJoCo could not load the model";
  return m;
}

}  // namespace

SceneLoadResult Scene::loadFile(const std::string& path, const std::vector<BodyClearance>& clearances) {
  installMujocoHandlers();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path).good())
    return fail(LoadStatus::FileNotFound, fmt::format("{}: scene file not found or not readable", path));
  std::string error;
  mjModel* m = loadXml(path.c_str(), error);
  if (!m) return fail(LoadStatus::ParseError, fmt::format("{}: {}", path, error));
  std::shared_ptr<Scene> scene(new Scene(m));
  if (std::string msg = scene->applyClearances(clearances); !msg.empty())
    return fail(LoadStatus::BadClearance, fmt::format("{}: {}", path, msg));
  if (std::string msg = scene->initialise(); !msg.empty())
    return fail(LoadStatus::NotARobotScene, fmt::format("{}: {}", path, msg));
  return {LoadStatus::Ok, {}, std::move(scene)};
}

Scene::Scene(mjModel* m) : model_(m), motionCache_(std::make_unique<MotionCache>()) {
  static std::atomic<std::uint64_t> next{1};
  serial_ = next.fetch_add(1);
}

Scene::~Scene() { mj_deleteModel(model_); }

std::string Scene::applyClearances(const std::vector<BodyClearance>& clearances) {
  const mjModel* m = model_;
  clearances_ = clearances;
  clearanceOf_.assign(static_cast<size_t>(m->nbody), -1);
  std::vector<char> marked(static_cast<size_t>(m->nbody));
  for (size_t c = 0; c < clearances_.size(); ++c) {
    const BodyClearance& bc = clearances_[c];
    const std::string at = bc.declaredAt.empty() ? "" : fmt::format(" ({})", bc.declaredAt);
    if (!(bc.distance >= 0) || !std::isfinite(bc.distance))
      return fmt::format("clearance '{}'{}: the distance must be a number >= 0", bc.name, at);
    std::fill(marked.begin(), marked.end(), 0);
    for (const std::string& name : bc.bodies) {
      const int root = bodyId(name);
      if (root < 0) return fmt::format("clearance '{}'{}: the scene has no body '{}'", bc.name, at, name);
      marked[static_cast<size_t>(root)] = 1;
    }
    // Parents precede children in MuJoCo's body order, so one pass marks every subtree.
    for (int b = 1; b < m->nbody; ++b)
      if (marked[static_cast<size_t>(m->body_parentid[b])]) marked[static_cast<size_t>(b)] = 1;
    for (int b = 0; b < m->nbody; ++b) {
      int& current = clearanceOf_[static_cast<size_t>(b)];
      if (marked[static_cast<size_t>(b)] &&
          (current < 0 || clearances_[static_cast<size_t>(current)].distance < bc.distance))
        current = static_cast<int>(c);
    }
  }
  return {};
}

std::string Scene::initialise() {
  const mjModel* m = model_;
  for (int i = 0; i < kArmDof; ++i) {
    const std::string name = fmt::format("joint_{}", i + 1);
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0 || m->jnt_type[j] != mjJNT_HINGE) return fmt::format("no hinge joint named '{}' (the Gen3 arm)", name);
    armJoint_[i] = j;
    armQpos_[i] = m->jnt_qposadr[j];
    armDof_[i] = m->jnt_dofadr[j];
    continuous_[i] = m->jnt_limited[j] == 0;
    lower_[i] = continuous_[i] ? -std::numbers::pi : m->jnt_range[2 * j];
    upper_[i] = continuous_[i] ? std::numbers::pi : m->jnt_range[2 * j + 1];
  }
  toolSite_ = siteId("tool_frame");
  if (toolSite_ < 0) return "no site named 'tool_frame'";
  const int armRoot = bodyId("base_link");
  const int ee = bodyId("end_effector_link");
  if (armRoot < 0 || ee < 0) return "no bodies named 'base_link' and 'end_effector_link'";

  static constexpr const char* kBaseJoints[3] = {"base_x", "base_y", "base_yaw"};
  std::array<int, 3> baseJointBody{-1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, kBaseJoints[i]);
    baseQpos_[i] = j >= 0 ? m->jnt_qposadr[j] : -1;
    baseJointBody[i] = j >= 0 ? m->jnt_bodyid[j] : -1;
  }
  // A subtree serves as a fast path only if it holds the bodies of every joint it stands for.
  auto subtreeOf = [m](int root, const int* jointBodies, int n) {
    KinematicSubtree tree(m, root);
    for (int i = 0; i < n; ++i)
      if (std::find(tree.bodies().begin(), tree.bodies().end(), jointBodies[i]) == tree.bodies().end())
        return KinematicSubtree();
    return tree;
  };
  if (baseJointBody[0] >= 0) baseSubtree_ = subtreeOf(baseJointBody[0], baseJointBody.data(), 3);
  std::array<int, kArmDof> armJointBody{};
  for (int i = 0; i < kArmDof; ++i) armJointBody[i] = m->jnt_bodyid[armJoint_[i]];
  armSubtree_ = subtreeOf(armJointBody[0], armJointBody.data(), kArmDof);
  if ((baseQpos_[0] >= 0) != (baseQpos_[2] >= 0) || (baseQpos_[1] >= 0) != (baseQpos_[2] >= 0))
    return "a mobile base needs all of base_x, base_y and base_yaw";
  static constexpr const char* kFingers[2] = {"finger_left", "finger_right"};
  for (int i = 0; i < 2; ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, kFingers[i]);
    fingerQpos_[i] = j >= 0 ? m->jnt_qposadr[j] : -1;
    if (j >= 0) fingerTravel_ = m->jnt_range[2 * j + 1];
  }

  // Classify bodies. Parents always precede children in MuJoCo's body order.
  const int mobile = bodyId("mobile_base");
  kinds_.assign(static_cast<size_t>(m->nbody), BodyKind::Scenery);
  objectOfBody_.assign(static_cast<size_t>(m->nbody), -1);
  for (int b = 1; b < m->nbody; ++b) {
    const int parent = m->body_parentid[b];
    const auto pk = kinds_[static_cast<size_t>(parent)];
    if (b == ee) {
      kinds_[b] = BodyKind::Gripper;
    } else if (b == armRoot || b == mobile) {
      kinds_[b] = BodyKind::Robot;
    } else if (pk == BodyKind::Robot || pk == BodyKind::Gripper) {
      kinds_[b] = pk;
    } else if (m->body_jntnum[b] > 0 && m->jnt_type[m->body_jntadr[b]] == mjJNT_FREE) {
      kinds_[b] = BodyKind::Object;
      objectOfBody_[b] = static_cast<int>(objects_.size());
      objects_.push_back({bodyName(b), b, m->jnt_qposadr[m->body_jntadr[b]]});
    } else if (pk == BodyKind::Object) {
      kinds_[b] = BodyKind::Object;
      objectOfBody_[b] = objectOfBody_[static_cast<size_t>(parent)];
    }
  }
  for (int b = 1; b < m->nbody; ++b)
    if (m->body_mocapid[b] >= 0) fixtures_.push_back({bodyName(b), b, m->body_mocapid[b]});
  for (const ObjectInfo& o : objects_) objectSubtrees_.emplace_back(m, o.body);
  buildPairs();
  endEffector_ = ee;
  geomDistance_ = std::make_unique<GeomDistance>(m);
  std::vector<bool> robotBody(static_cast<size_t>(m->nbody), false);
  for (int b = 0; b < m->nbody; ++b)
    robotBody[static_cast<size_t>(b)] =
        kinds_[static_cast<size_t>(b)] == BodyKind::Robot || kinds_[static_cast<size_t>(b)] == BodyKind::Gripper;
  motionBound_ = std::make_unique<MotionBound>(m, robotBody);
  return {};
}

// The filters of MuJoCo 2.2.2's collision driver for a geom pair (explicit <pair> elements aside).
bool Scene::mujocoWouldCollide(int g1, int g2) const {
  const mjModel* m = model_;
  if (!((m->geom_contype[g1] & m->geom_conaffinity[g2]) || (m->geom_contype[g2] & m->geom_conaffinity[g1])))
    return false;
  const int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
  const int w1 = m->body_weldid[b1], w2 = m->body_weldid[b2];
  if (w1 == w2) return false;
  const int p1 = m->body_weldid[m->body_parentid[w1]], p2 = m->body_weldid[m->body_parentid[w2]];
  const bool filterParent = !(m->opt.disableflags & mjDSBL_FILTERPARENT);
  if (filterParent && w1 != 0 && w2 != 0 && (w1 == p2 || w2 == p1)) return false;
  const int lo = std::min(b1, b2), hi = std::max(b1, b2);
  const int signature = ((lo + 1) << 16) + hi + 1;
  for (int e = 0; e < m->nexclude; ++e)
    if (m->exclude_signature[e] == signature) return false;
  return true;
}

void Scene::buildPairs() {
  const mjModel* m = model_;
  objectPairs_.assign(objects_.size(), {});
  reachMargin_.assign(static_cast<size_t>(m->ngeom), 0.0);
  for (int g = 0; g < m->ngeom; ++g) reachMargin_[static_cast<size_t>(g)] = m->geom_margin[g];
  auto robotGeom = [&](int g) {
    const BodyKind k = kinds_[static_cast<size_t>(m->geom_bodyid[g])];
    return k == BodyKind::Robot || k == BodyKind::Gripper;
  };
  for (int g = 0; g < m->ngeom; ++g)
    if (robotGeom(g)) robotGeoms_.push_back(g);
  auto clearanceOfGeom = [&](int g) { return clearanceDistance(m->geom_bodyid[g]); };
  auto add = [&](int a, int b, double margin) {
    auto pair = [&](double keepOut) {
      reachMargin_[static_cast<size_t>(a)] = std::max(reachMargin_[static_cast<size_t>(a)], keepOut);
      reachMargin_[static_cast<size_t>(b)] = std::max(reachMargin_[static_cast<size_t>(b)], keepOut);
      return m->geom_type[a] <= m->geom_type[b] ? GeomPair{a, b, keepOut} : GeomPair{b, a, keepOut};
    };
    const bool ra = robotGeom(a), rb = robotGeom(b);
    if (ra && rb) {
      selfPairs_.push_back(pair(margin));
    } else if (ra || rb) {
      robotPairs_.push_back(pair(std::max(margin, clearanceOfGeom(ra ? b : a))));
    } else {
      const int oa = objectOfBody_[static_cast<size_t>(m->geom_bodyid[a])];
      const int ob = objectOfBody_[static_cast<size_t>(m->geom_bodyid[b])];
      if (oa >= 0 && oa != ob)
        objectPairs_[static_cast<size_t>(oa)].push_back(pair(std::max(margin, clearanceOfGeom(b))));
      if (ob >= 0 && ob != oa)
        objectPairs_[static_cast<size_t>(ob)].push_back(pair(std::max(margin, clearanceOfGeom(a))));
    }
  };
  for (int i = 0; i < m->npair; ++i)
    explicitMargin_[std::minmax(m->pair_geom1[i], m->pair_geom2[i])] = m->pair_margin[i];
  for (int a = 0; a < m->ngeom; ++a)
    for (int b = a + 1; b < m->ngeom; ++b)
      if (mujocoWouldCollide(a, b) && !explicitMargin_.count({a, b}))
        add(a, b, std::max(m->geom_margin[a], m->geom_margin[b]));
  for (int i = 0; i < m->npair; ++i) add(m->pair_geom1[i], m->pair_geom2[i], m->pair_margin[i]);
}

double Scene::keepOut(int g1, int g2) const {
  double keep = 0.0;
  if (const auto it = explicitMargin_.find(std::minmax(g1, g2)); it != explicitMargin_.end())
    keep = it->second;
  else if (mujocoWouldCollide(g1, g2))
    keep = std::max(model_->geom_margin[g1], model_->geom_margin[g2]);
  else
    return 0.0;
  for (const int g : {g1, g2}) {
    const BodyKind k = kinds_[static_cast<size_t>(model_->geom_bodyid[g])];
    if (k != BodyKind::Robot && k != BodyKind::Gripper)
      keep = std::max(keep, clearanceDistance(model_->geom_bodyid[g]));
  }
  return keep;
}

bool Scene::withinLimits(const ArmConfig& q) const {
  for (int i = 0; i < kArmDof; ++i) {
    if (!std::isfinite(q[i])) return false;
    if (!continuous_[i] && (q[i] < lower_[i] || q[i] > upper_[i])) return false;
  }
  return true;
}

ArmConfig Scene::normalize(const ArmConfig& q) const {
  ArmConfig r = q;
  for (int i = 0; i < kArmDof; ++i) r[i] = continuous_[i] ? wrapAngle(q[i]) : std::clamp(q[i], lower_[i], upper_[i]);
  return r;
}

int Scene::siteId(std::string_view name) const { return mj_name2id(model_, mjOBJ_SITE, std::string(name).c_str()); }
int Scene::bodyId(std::string_view name) const { return mj_name2id(model_, mjOBJ_BODY, std::string(name).c_str()); }
int Scene::geomId(std::string_view name) const { return mj_name2id(model_, mjOBJ_GEOM, std::string(name).c_str()); }

std::string Scene::bodyName(int body) const {
  const char* n = mj_id2name(model_, mjOBJ_BODY, body);
  return n ? n : fmt::format("body#{}", body);
}

std::string Scene::geomName(int geom) const {
  const char* n = mj_id2name(model_, mjOBJ_GEOM, geom);
  return n ? n : fmt::format("geom#{}", geom);
}

int Scene::objectIndex(std::string_view name) const {
  for (size_t i = 0; i < objects_.size(); ++i)
    if (objects_[i].name == name) return static_cast<int>(i);
  return -1;
}

int Scene::fixtureIndex(std::string_view name) const {
  for (size_t i = 0; i < fixtures_.size(); ++i)
    if (fixtures_[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace cbtl::world
