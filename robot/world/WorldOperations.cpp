#include "robot/world/WorldOperations.h"

#include "robot/world/SurfaceFace.h"

#include <fmt/core.h>

#include <cmath>
#include <numbers>

namespace cbtl::world {

World::World(std::shared_ptr<const Scene> scene)
    : ws_(scene), clearance_(scene), occlusion_(occlusionSpecFor(*scene)) {}

namespace builtins {

const char* toString(ActionStatus s) {
  switch (s) {
    case ActionStatus::Done:
      return "done";
    case ActionStatus::InvalidArgument:
      return "invalid argument";
    case ActionStatus::NoPath:
      return "no collision-free path";
    case ActionStatus::NoIk:
      return "no collision-free IK solution";
    case ActionStatus::OutOfReach:
      return "object out of reach";
    case ActionStatus::NotHolding:
      return "not holding anything";
    case ActionStatus::AlreadyHolding:
      return "already holding an object";
    case ActionStatus::Blocked:
      return "placement blocked";
  }
  return "unknown";
}

namespace {

const Eigen::Quaterniond kToolDown(0, 1, 0, 0);  // tool z along world -z

// Restores the state saved at the start of an action unless the action completes.
class StateGuard {
 public:
  explicit StateGuard(World& w) : w_(w), saved_(w.workspace().state()) {}
  ~StateGuard() {
    if (!committed_) w_.workspace().setState(saved_);
  }
  void commit() { committed_ = true; }

 private:
  World& w_;
  WorldState saved_;
  bool committed_ = false;
};

ActionResult fail(ActionStatus s, std::string detail) {
  ActionResult r;
  r.status = s;
  r.detail = std::move(detail);
  return r;
}

// Moves the arm from its current configuration to q: a straight segment if free, else a planned path.
// Appends the executed waypoints (without the start) to `path`.
bool moveArmInternal(World& w, const ArmConfig& q, Rng& rng, std::vector<ArmConfig>& path, std::string& detail) {
  Workspace& ws = w.workspace();
  const ArmConfig start = ws.state().arm;
  if (armSegmentFree(ws, start, q, w.planning.resolution, w.planning.collision)) {
    path.push_back(q);
    ws.setArm(q);
    return true;
  }
  const ArmPlan plan = planArm(ws, start, q, rng, w.planning);
  if (!plan.solved()) {
    ws.setArm(start);
    detail = toString(plan.status);
    return false;
  }
  path.insert(path.end(), plan.path.begin() + 1, plan.path.end());
  ws.setArm(q);
  return true;
}

}  // namespace

Pose3 poseAbove(const Pose3& p, double height) {
  Pose3 r = p;
  r.position.z() += height;
  return r;
}

Pose3 relativePose(const Pose3& from, const Pose3& to) { return from.inverse() * to; }
Pose3 composePose(const Pose3& a, const Pose3& b) { return a * b; }
double distance(const Pose3& a, const Pose3& b) { return (a.position - b.position).norm(); }

double objectDistance(World& w, const std::string& a, const Pose3& poseA, const std::string& b, const Pose3& poseB) {
  return w.clearance().objectDistance(a, poseA, b, poseB);
}

std::optional<Pose3> objectPose(World& w, const std::string& object) { return w.workspace().objectPose(object); }
Pose3 toolPose(World& w) { return w.workspace().toolPose(); }

bool collisionFreeConf(World& w, const ArmConfig& q) {
  Workspace& ws = w.workspace();
  if (!ws.scene().withinLimits(q)) return false;
  const ArmConfig keep = ws.state().arm;
  const bool free = checkArm(ws, q, w.planning.collision).free();
  ws.setArm(keep);
  return free;
}

bool collisionFreePoses(World& w, const std::string& a, const Pose3& poseA, const std::string& b, const Pose3& poseB) {
  return w.clearance().objectDistance(a, poseA, b, poseB) > 0.0;
}

bool placementClear(World& w, const std::string& object, const Pose3& pose, double clearance) {
  PlacementOptions o;
  o.clearance = clearance;
  return w.clearance().checkPlacement(w.workspace(), object, pose, o).ok();
}

Pose3 forwardKinematics(World& w, const ArmConfig& q) {
  Workspace& ws = w.workspace();
  const ArmConfig keep = ws.state().arm;
  const Pose3 p = ws.forwardKinematics(q);
  ws.setArm(keep);
  return p;
}

bool ikFeasible(World& w, const Pose3& tool, Rng& rng) {
  Workspace& ws = w.workspace();
  const ArmConfig keep = ws.state().arm;
  const bool ok = solveIk(ws, tool, keep, rng, w.ik).solved();
  ws.setArm(keep);
  return ok;
}

std::optional<ArmConfig> sampleIk(World& w, const Pose3& tool, Rng& rng) {
  Workspace& ws = w.workspace();
  const ArmConfig keep = ws.state().arm;
  const ArmConfig seed = randomConfig(ws.scene(), rng);
  const IkResult r = solveIk(ws, tool, seed, rng, w.ik);
  ws.setArm(keep);
  if (!r.solved()) return std::nullopt;
  return r.q;
}

std::optional<Pose3> samplePlacement(World& w, const std::string& object, const std::string& surface, double clearance,
                                     Rng& rng, int tries) {
  const auto face = surfaceFace(w.workspace(), surface);
  const auto box = w.clearance().objectBox(object);
  if (!face || !box) return std::nullopt;
  for (int i = 0; i < tries; ++i) {
    const double yaw = rng.uniform(-std::numbers::pi, std::numbers::pi);
    const double c = std::abs(std::cos(yaw)), s = std::abs(std::sin(yaw));
    const double fx = c * box->halfExtents.x() + s * box->halfExtents.y();
    const double fy = s * box->halfExtents.x() + c * box->halfExtents.y();
    if (fx > face->halfX || fy > face->halfY) continue;
    // x before y, in separate statements (the order of evaluation of function arguments is unspecified).
    const double x = rng.uniform(face->center.x() - face->halfX + fx, face->center.x() + face->halfX - fx);
    const double y = rng.uniform(face->center.y() - face->halfY + fy, face->center.y() + face->halfY - fy);
    const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    const Eigen::Vector3d boxCenter(x, y, face->center.z() + box->halfExtents.z());
    const Pose3 pose{boxCenter - q * box->center, q};
    if (placementClear(w, object, pose, clearance)) return pose;
  }
  return std::nullopt;
}

double occlusion(World& w, const ArmConfig& q) {
  if (!w.occlusion()) return 0.0;
  Workspace& ws = w.workspace();
  const ArmConfig keep = ws.state().arm;
  ws.setArm(q);
  const double score = occlusionScore(ws, *w.occlusion());
  ws.setArm(keep);
  return score;
}

bool motionFeasible(World& w, const ArmConfig& from, const ArmConfig& to, Rng& rng) {
  Workspace& ws = w.workspace();
  const ArmConfig keep = ws.state().arm;
  const bool ok = planArm(ws, from, to, rng, w.planning).solved();
  ws.setArm(keep);
  return ok;
}

ActionResult moveArm(World& w, const ArmConfig& goal, Rng& rng) {
  StateGuard guard(w);
  ActionResult r;
  r.armPath.push_back(w.workspace().state().arm);
  if (!moveArmInternal(w, goal, rng, r.armPath, r.detail)) return fail(ActionStatus::NoPath, r.detail);
  guard.commit();
  return r;
}

ActionResult moveArmToPose(World& w, const Pose3& tool, Rng& rng) {
  StateGuard guard(w);
  Workspace& ws = w.workspace();
  const ArmConfig start = ws.state().arm;
  const IkResult ik = solveIk(ws, tool, start, rng, w.ik);
  ws.setArm(start);
  if (!ik.solved()) return fail(ActionStatus::NoIk, toString(ik.status));
  ActionResult r;
  r.armPath.push_back(start);
  if (!moveArmInternal(w, ik.q, rng, r.armPath, r.detail)) return fail(ActionStatus::NoPath, r.detail);
  guard.commit();
  return r;
}

ActionResult moveBase(World& w, const Pose2& goal, Rng& rng) {
  StateGuard guard(w);
  Workspace& ws = w.workspace();
  if (!ws.scene().hasMobileBase()) return fail(ActionStatus::InvalidArgument, "the scene has no mobile base");
  const BasePlan plan = planBase(ws, goal, rng, w.planning);
  if (!plan.solved()) return fail(ActionStatus::NoPath, toString(plan.status));
  ws.setBase(goal);
  ActionResult r;
  r.basePath = plan.path;
  guard.commit();
  return r;
}

ActionResult grasp(World& w, const std::string& object, double maxDistance) {
  Workspace& ws = w.workspace();
  if (ws.heldObject() >= 0) return fail(ActionStatus::AlreadyHolding, ws.state().held->object);
  const auto pose = ws.objectPose(object);
  if (!pose) return fail(ActionStatus::InvalidArgument, fmt::format("no movable object '{}'", object));
  const int tip = ws.scene().siteId("finger_tip");
  const Pose3 grip = tip >= 0 ? ws.sitePose(tip) : ws.toolPose();
  const double d = (grip.position - pose->position).norm();
  if (d > maxDistance) return fail(ActionStatus::OutOfReach, fmt::format("{} is {:.3f} m from the gripper", object, d));
  WorldState st = ws.state();
  st.gripper = 0.0;
  st.held.reset();
  ws.setState(st);
  ws.setHeld(object);
  return {};
}

ActionResult release(World& w) {
  Workspace& ws = w.workspace();
  if (ws.heldObject() < 0) return fail(ActionStatus::NotHolding, "");
  ws.setHeld(std::nullopt);
  WorldState st = ws.state();
  st.gripper = 1.0;
  ws.setState(st);
  return {};
}

ActionResult moveObjectTo(World& w, const std::string& object, double x, double y) {
  Workspace& ws = w.workspace();
  auto pose = ws.objectPose(object);
  if (!pose) return fail(ActionStatus::InvalidArgument, fmt::format("no movable object '{}'", object));
  if (ws.scene().objectIndex(object) == ws.heldObject())
    return fail(ActionStatus::InvalidArgument, fmt::format("'{}' is held by the robot", object));
  pose->position.x() = x;
  pose->position.y() = y;
  PlacementOptions o;
  o.clearance = 0.0;
  const PlacementReport rep = w.clearance().checkPlacement(ws, object, *pose, o);
  if (!rep.ok()) return fail(ActionStatus::Blocked, fmt::format("{} would touch {}", object, rep.other));
  ws.setObjectPose(object, *pose);
  return {};
}

ActionResult movePlate(World& w, double x, double y) { return moveObjectTo(w, "plate", x, y); }
ActionResult moveDrink(World& w, double x, double y) { return moveObjectTo(w, "drink", x, y); }

ActionResult handOver(World& w, const Eigen::Vector3d& position, Rng& rng) {
  if (w.workspace().heldObject() < 0) return fail(ActionStatus::NotHolding, "nothing to hand over");
  // rpy(-π/4, π/2, 0) as R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Quaterniond q = Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-std::numbers::pi / 4, Eigen::Vector3d::UnitX());
  ActionResult r = moveArmToPose(w, Pose3{position, q}, rng);
  if (r.done()) w.utterances().push_back("Here you go!");
  return r;
}

ActionResult wipe(World& w, const std::string& surface, Rng& rng, double toolHeight) {
  Workspace& ws = w.workspace();
  if (ws.heldObject() < 0) return fail(ActionStatus::NotHolding, "wiping needs a held tool");
  const auto face = surfaceFace(ws, surface);
  if (!face) return fail(ActionStatus::InvalidArgument, fmt::format("no box surface '{}'", surface));
  StateGuard guard(w);
  // Passes run along the longer side; their number covers the shorter side in 0.15 m strips.
  const bool alongX = face->halfX >= face->halfY;
  const double length = 2 * (alongX ? face->halfX : face->halfY);
  const double width = 2 * (alongX ? face->halfY : face->halfX);
  const int passes = std::max(1, static_cast<int>(std::ceil(width / 0.15)));
  ActionResult r;
  r.armPath.push_back(ws.state().arm);
  for (int k = 0; k < passes; ++k) {
    const double across = -width / 2 + width * (k + 0.5) / passes;
    for (int end = 0; end < 2; ++end) {
      const double along = ((k % 2 == 0) == (end == 0) ? -1.0 : 1.0) * length / 2 * 0.8;
      Eigen::Vector3d p = face->center;
      p.z() += toolHeight;
      (alongX ? p.x() : p.y()) += along;
      (alongX ? p.y() : p.x()) += across;
      const ArmConfig current = ws.state().arm;
      const IkResult ik = solveIk(ws, Pose3{p, kToolDown}, current, rng, w.ik);
      ws.setArm(current);
      if (!ik.solved())
        return fail(ActionStatus::NoIk, fmt::format("pass {} of {}: {}", k + 1, passes, toString(ik.status)));
      if (!moveArmInternal(w, ik.q, rng, r.armPath, r.detail)) return fail(ActionStatus::NoPath, r.detail);
    }
  }
  guard.commit();
  return r;
}

ActionResult say(World& w, const std::string& text) {
  w.utterances().push_back(text);
  return {};
}

}  // namespace builtins
}  // namespace cbtl::world
