#include "robot/world/WorldOperations.h"

#include "robot/world/GraspClosure.h"
#include "robot/world/MotionQuery.h"
#include "robot/world/SurfaceFace.h"

#include <fmt/core.h>

#include <cmath>
#include <numbers>

namespace cbtl::world {

World::World(std::shared_ptr<const Scene> scene)
    : ws_(scene), clearance_(scene), occlusion_(occlusionSpecFor(*scene)) {}

void World::noteArmMotion(const std::vector<ArmConfig>& path, const CollisionOptions& collision) {
  if (!recording_ || path.size() < 2) return;
  ExecutedMotion m;
  m.kind = ExecutedMotion::Kind::Arm;
  m.start = ws_.state();
  m.start.arm = path.front();
  m.arm = path;
  m.allowances = collision.allowances;
  motions_.push_back(std::move(m));
}

void World::noteBaseMotion(const std::vector<Pose2>& path, const CollisionOptions& collision) {
  if (!recording_ || path.size() < 2) return;
  ExecutedMotion m;
  m.kind = ExecutedMotion::Kind::Base;
  m.start = ws_.state();
  m.start.base = path.front();
  m.base = path;
  m.allowances = collision.allowances;
  motions_.push_back(std::move(m));
}

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
    case ActionStatus::NoGrip:
      return "no grip";
  }
  return "unknown";
}

namespace {

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

// Moves the arm from its current configuration to q (planArmCached: the straight segment first, then
// RRTConnect, with the query's own random stream). Appends the executed waypoints (without the start) to `path`.
bool moveArmInternal(World& w, const ArmConfig& q, std::vector<ArmConfig>& path, std::string& detail) {
  Workspace& ws = w.workspace();
  const ArmConfig start = ws.state().arm;
  const ArmPlan plan = planArmCached(ws, q, w.planning);
  if (!plan.solved()) {
    detail = toString(plan.status);
    // Say which pair, and which clearance, makes the start or the goal invalid: the dry run's verdict, and so the
    // task's explanation, then names the declaration.
    if (plan.status == PlanStatus::InvalidGoal || plan.status == PlanStatus::InvalidStart) {
      ws.setArm(plan.status == PlanStatus::InvalidGoal ? q : start);
      if (const CollisionReport c = checkRobotCollisions(ws, w.planning.collision); !c.free())
        detail += ": " + c.describe();
    }
    ws.setArm(start);
    return false;
  }
  path.insert(path.end(), plan.path.begin() + 1, plan.path.end());
  ws.setArm(q);
  w.noteArmMotion(plan.path, w.planning.collision);
  return true;
}

}  // namespace

bool placementClear(World& w, const std::string& object, const Pose3& pose, double clearance) {
  PlacementOptions o;
  o.clearance = clearance;
  return w.clearance().checkPlacement(w.workspace(), object, pose, o).ok();
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

ActionResult moveArm(World& w, const ArmConfig& goal) {
  StateGuard guard(w);
  ActionResult r;
  r.armPath.push_back(w.workspace().state().arm);
  if (!moveArmInternal(w, goal, r.armPath, r.detail)) return fail(ActionStatus::NoPath, r.detail);
  guard.commit();
  return r;
}

ActionResult moveBase(World& w, const Pose2& goal) {
  StateGuard guard(w);
  Workspace& ws = w.workspace();
  if (!ws.scene().hasMobileBase()) return fail(ActionStatus::InvalidArgument, "the scene has no mobile base");
  const BasePlan plan = planBaseCached(ws, goal, w.planning);
  if (!plan.solved()) {
    std::string detail = toString(plan.status);
    if (plan.status == PlanStatus::InvalidGoal) {
      ws.setBase(goal);  // the guard puts the base back
      if (const CollisionReport c = checkRobotCollisions(ws, w.planning.collision); !c.free())
        detail += ": " + c.describe();
    }
    return fail(ActionStatus::NoPath, detail);
  }
  ws.setBase(goal);
  w.noteBaseMotion(plan.path, w.planning.collision);
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
  const int index = ws.scene().objectIndex(object);
  const GraspClosure closure = closeOn(ws, index);
  if (!closure.holds()) return fail(ActionStatus::NoGrip, closure.detail);
  WorldState st = ws.state();
  st.gripper = closure.gripper;
  st.held.reset();
  Pose3 pushed = *pose;
  pushed.position += closure.pushWorld;
  st.objects[object] = pushed;
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

ActionResult say(World& w, const std::string& text) {
  w.utterances().push_back(text);
  return {};
}

}  // namespace builtins
}  // namespace cbtl::world
