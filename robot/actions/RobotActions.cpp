#include "robot/actions/RobotActions.h"

#include "robot/actions/ClearanceExceptions.h"

#include "robot/world/CartesianPath.h"
#include "robot/world/GraspClosure.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/MotionQuery.h"
#include "robot/world/NamedConfigurations.h"
#include "robot/world/Separation.h"
#include "robot/world/Support.h"

#include "robot/actions/CallArguments.h"
#include "robot/actions/StandardGrasps.h"
#include "robot/actions/SurfaceGeometry.h"
#include "robot/actions/WipeSweep.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace cbtl::actions {

using world::builtins::ActionResult;
using world::builtins::ActionStatus;

namespace {

RobotActionResult illFormed(std::string message) {
  RobotActionResult r;
  r.wellFormed = false;
  r.status = ActionStatus::InvalidArgument;
  r.detail = std::move(message);
  r.steps = 0;
  return r;
}

RobotActionResult failed(ActionStatus s, std::string detail) {
  RobotActionResult r;
  r.status = s;
  r.detail = std::move(detail);
  return r;
}

RobotActionResult from(ActionResult a) {
  RobotActionResult r;
  r.status = a.status;
  r.detail = std::move(a.detail);
  r.armPath = std::move(a.armPath);
  r.basePath = std::move(a.basePath);
  return r;
}

// Puts the World back as it was unless the action commits (multi-stage actions: grasp, release, place).
class Restore {
 public:
  explicit Restore(world::World& w) : w_(w), saved_(w.workspace().state()) {}
  ~Restore() {
    if (!committed_) w_.workspace().setState(saved_);
  }
  Restore(const Restore&) = delete;
  Restore& operator=(const Restore&) = delete;
  void commit() { committed_ = true; }

 private:
  world::World& w_;
  world::WorldState saved_;
  bool committed_ = false;
};

// Contacts an action allows for the motions it makes while this lives (world/Collision.h ContactAllowance): added
// to the World's planning and IK options, taken back at the end of the scope.
class ScopedAllowances {
 public:
  ScopedAllowances(world::World& w, const std::vector<world::ContactAllowance>& allowed)
      : w_(w), planning_(w.planning.collision), ik_(w.ik.collision) {
    for (const auto& a : allowed) {
      w.planning.collision.allowances.push_back(a);
      w.ik.collision.allowances.push_back(a);
    }
  }
  ~ScopedAllowances() {
    w_.planning.collision = planning_;
    w_.ik.collision = ik_;
  }
  ScopedAllowances(const ScopedAllowances&) = delete;
  ScopedAllowances& operator=(const ScopedAllowances&) = delete;

 private:
  world::World& w_;
  world::CollisionOptions planning_, ik_;
};

bool posesClose(const world::Pose3& a, const world::Pose3& b, double position, double angle) {
  return (a.position - b.position).norm() <= position && world::rotationDistance(a.orientation, b.orientation) <= angle;
}

// The IK restarts' random stream for reaching `target` from the Workspace's state: a function of both.
world::Rng ikStream(const world::Workspace& ws, const world::Pose3& target) {
  const world::WorldState& s = ws.state();
  std::vector<double> key(s.arm.begin(), s.arm.end());
  key.insert(key.end(), {s.base.x, s.base.y, s.base.yaw, static_cast<double>(ws.heldObject()), target.position.x(),
                         target.position.y(), target.position.z(), target.orientation.w(), target.orientation.x(),
                         target.orientation.y(), target.orientation.z()});
  return world::Rng(world::fingerprintOf(key));
}

// The standard action names, sorted (isStandard).
const std::vector<std::string> kNames = [] {
  std::vector<std::string> n{
      "moveArm", "moveTool", "moveToolStraight", "moveArmToNamed", "moveBase", "grasp",       "closeGripper",
      "release", "place",    "handOver",         "wipe",           "say",      "waitForUser", "wait"};
  std::sort(n.begin(), n.end());
  return n;
}();

}  // namespace

sim::ActionStatus RobotActionResult::simStatus() const {
  if (!wellFormed) return sim::ActionStatus::UnknownAction;
  return done() ? sim::ActionStatus::Applied : sim::ActionStatus::Ignored;
}

sim::StepResult RobotActionResult::toStepResult(const std::string& action) const {
  sim::StepResult s;
  s.status = simStatus();
  s.consumedStep = consumedStep();
  if (!wellFormed) {
    s.message = detail;
  } else if (!done()) {
    s.message = action + ": " + world::builtins::toString(status) + (detail.empty() ? "" : ": " + detail);
  } else {
    s.message = detail;
  }
  return s;
}

bool RobotActions::isStandard(std::string_view name) { return std::binary_search(kNames.begin(), kNames.end(), name); }

ActionResult moveArmIn(world::World& w, const world::ArmConfig& q, ExecutionMode mode) {
  if (mode == ExecutionMode::Execute) return world::builtins::moveArm(w, q);
  ActionResult r;
  if (!w.workspace().scene().withinLimits(q)) {
    r.status = ActionStatus::NoPath;
    r.detail = world::toString(world::PlanStatus::InvalidGoal);
    return r;
  }
  r.armPath = {w.workspace().state().arm, q};
  w.workspace().setArm(q);
  return r;
}

ActionResult moveToolIn(world::World& w, const world::Pose3& target, ExecutionMode mode) {
  world::Workspace& ws = w.workspace();
  const world::ArmConfig start = ws.state().arm;
  world::Rng rng = ikStream(ws, target);
  const world::IkResult ik = world::solveIk(ws, target, start, rng, w.ik);
  ws.setArm(start);
  if (!ik.solved()) {
    ActionResult r;
    r.status = ActionStatus::NoIk;
    r.detail = world::toString(ik.status);
    return r;
  }
  if (mode != ExecutionMode::Execute) return moveArmIn(w, ik.q, mode);
  // The straight joint segment first; where it bows off the tool's line into something, the line itself;
  // the planner last.
  ActionResult r;
  if (world::armSegmentFree(ws, start, ik.q, w.planning.collision)) {
    r.armPath = {start, ik.q};
    ws.setArm(ik.q);
    w.noteArmMotion(r.armPath, w.planning.collision);
    return r;
  }
  ws.setArm(start);
  world::CartesianPathOptions line;
  line.collision = w.planning.collision;
  if (auto path = world::cartesianToolPath(ws, target, w.ik, line)) {
    r.armPath = std::move(*path);
    ws.setArm(r.armPath.back());
    w.noteArmMotion(r.armPath, line.collision);
    return r;
  }
  return moveArmIn(w, ik.q, mode);
}

// The tool along the straight line to `target` (CartesianPath.h), or a failure: never a joint-space detour. Effects
// mode follows the same IK chain without the collision checks (they decide acceptance, not the configurations), so
// it ends where Execute does whenever Execute succeeds.
ActionResult moveToolStraightIn(world::World& w, const world::Pose3& target, ExecutionMode mode) {
  world::Workspace& ws = w.workspace();
  world::CartesianPathOptions line;
  line.collision = w.planning.collision;
  line.checkCollisions = mode == ExecutionMode::Execute;
  ActionResult r;
  auto path = world::cartesianToolPath(ws, target, w.ik, line);
  if (!path) {
    r.status = ActionStatus::NoPath;
    r.detail = "no straight tool line to the target keeps every required separation";
    return r;
  }
  r.armPath = std::move(*path);
  ws.setArm(r.armPath.back());
  if (mode == ExecutionMode::Execute) w.noteArmMotion(r.armPath, line.collision);
  return r;
}

std::vector<world::ContactAllowance> restingContacts(world::World& w) {
  world::Workspace& ws = w.workspace();
  std::vector<world::ContactAllowance> out;
  const int held = ws.heldObject();
  if (held < 0) return out;
  for (const auto& p : ws.scene().objectPairs(held)) {
    const bool firstHeld = ws.scene().objectOfBody(ws.model()->geom_bodyid[p.g1]) == held;
    const int other = firstHeld ? p.g2 : p.g1;
    if (world::exactSeparation(ws, p.g1, p.g2, kRestingContact, false) > kRestingContact) continue;
    world::ContactAllowance a;
    a.part = world::ContactAllowance::Part::HeldObject;
    a.geom = other;
    a.separation = -kRestingContact;
    if (std::find(out.begin(), out.end(), a) == out.end()) out.push_back(a);
  }
  return out;
}

std::optional<RobotActionResult> RobotActions::execute(world::World& w, const sim::ActionCall& call,
                                                       ExecutionMode mode) const {
  // The skill's declared exceptions to the clearances hold for every check of this action.
  std::vector<world::ContactAllowance> declared;
  std::string error;
  if (!resolveClearanceExceptions(w.workspace().scene(), call.exceptions, declared, error)) {
    if (!domain_ && !isStandard(call.name)) return std::nullopt;
    return failed(ActionStatus::InvalidArgument, error);
  }
  ScopedAllowances scope(w, declared);
  if (domain_) {
    if (auto r = domain_->execute(w, call, mode)) return r;
  }
  if (!isStandard(call.name)) return std::nullopt;
  return standard(w, call, mode);
}

RobotActionResult RobotActions::standard(world::World& w, const sim::ActionCall& call, ExecutionMode mode) const {
  const std::string& n = call.name;
  const std::vector<sim::Value>& a = call.args;

  if (n == "moveArm") {
    if (auto e = checkArguments(call, {kConfArg}); !e.empty()) return illFormed(e);
    const auto q = decodeConf(a[0].vector);
    if (!q) return failed(ActionStatus::InvalidArgument, "moveArm: a joint angle is not finite");
    return from(moveArmIn(w, *q, mode));
  }
  if (n == "moveTool") {
    if (auto e = checkArguments(call, {kSe3Arg}); !e.empty()) return illFormed(e);
    const auto tool = decodePose3(a[0].vector);
    if (!tool)
      return failed(ActionStatus::InvalidArgument, "moveTool: the pose is not finite or its quaternion is zero");
    return from(moveToolIn(w, *tool, mode));
  }
  if (n == "moveToolStraight") {
    if (auto e = checkArguments(call, {kSe3Arg}); !e.empty()) return illFormed(e);
    const auto tool = decodePose3(a[0].vector);
    if (!tool)
      return failed(ActionStatus::InvalidArgument,
                    "moveToolStraight: the pose is not finite or its quaternion is zero");
    return from(moveToolStraightIn(w, *tool, mode));
  }
  if (n == "moveArmToNamed") {
    if (auto e = checkArguments(call, {kNameArg}); !e.empty()) return illFormed(e);
    // The scene's own names first, as std.kinova's namedConf reads them.
    const auto q = world::namedConfiguration(w.workspace().scene(), a[0].text);
    if (!q) {
      std::string known;
      for (const std::string& name : world::namedConfigurationNames(w.workspace().scene()))
        known += (known.empty() ? "" : ", ") + name;
      return failed(ActionStatus::InvalidArgument,
                    fmt::format("no named configuration '{}' (known: {})", a[0].text, known));
    }
    return from(moveArmIn(w, *q, mode));
  }
  if (n == "moveBase") {
    if (auto e = checkArguments(call, {kSe2Arg}); !e.empty()) return illFormed(e);
    const auto pose = decodePose2(a[0].vector);
    if (!pose) return failed(ActionStatus::InvalidArgument, "moveBase: the pose is not finite");
    if (mode == ExecutionMode::Effects) {
      if (!w.workspace().scene().hasMobileBase())
        return failed(ActionStatus::InvalidArgument, "the scene has no mobile base");
      w.workspace().setBase(*pose);
      return RobotActionResult{};
    }
    return from(world::builtins::moveBase(w, *pose));
  }
  if (n == "grasp") {
    if (auto e = checkArguments(call, {kNameArg}); !e.empty()) return illFormed(e);
    return grasp(w, a[0].text, mode);
  }
  if (n == "closeGripper") {
    if (auto e = checkArguments(call, {kNumberArg}); !e.empty()) return illFormed(e);
    const double closure = a[0].number;
    if (!(closure >= 0 && closure <= 1)) {
      return failed(ActionStatus::InvalidArgument, fmt::format("closeGripper: closure {} is outside [0, 1]", closure));
    }
    return closeGripper(w, closure);
  }
  if (n == "release") {
    if (auto e = checkArguments(call, {}); !e.empty()) return illFormed(e);
    return release(w);
  }
  if (n == "place") {
    if (auto e = checkArguments(call, {kNameArg, kSe3Arg}); !e.empty()) return illFormed(e);
    const auto pose = decodePose3(a[1].vector);
    if (!pose) return failed(ActionStatus::InvalidArgument, "place: the pose is not finite or its quaternion is zero");
    return place(w, a[0].text, *pose, mode);
  }
  if (n == "handOver") {
    if (auto e = checkArguments(call, {}); !e.empty()) return illFormed(e);
    return handOver(w);
  }
  if (n == "wipe") {
    if (auto e = checkArguments(call, {kNameArg, kSe2Arg}); !e.empty()) return illFormed(e);
    const auto base = decodePose2(a[1].vector);
    if (!base) return failed(ActionStatus::InvalidArgument, "wipe: the base pose is not finite");
    if (mode == ExecutionMode::Effects) {
      // The sweep ends where it began: the base back at `base`, the arm as it was.
      if (w.workspace().heldObject() < 0) return failed(ActionStatus::NotHolding, "wiping needs a held duster");
      if (!w.workspace().scene().hasMobileBase())
        return failed(ActionStatus::InvalidArgument, "the scene has no mobile base");
      w.workspace().setBase(*base);
      return RobotActionResult{};
    }
    return from(sweepSurface(w, a[0].text, *base, mode == ExecutionMode::Effects));
  }
  if (n == "say") {
    if (auto e = checkArguments(call, {kNameArg}); !e.empty()) return illFormed(e);
    return from(world::builtins::say(w, a[0].text));
  }
  if (n == "waitForUser") {
    if (auto e = checkArguments(call, {kNameArg}); !e.empty()) return illFormed(e);
    return RobotActionResult{};
  }
  // wait(n)
  if (auto e = checkArguments(call, {kNumberArg}); !e.empty()) return illFormed(e);
  const double count = a[0].number;
  if (!(count >= 0) || count != std::floor(count) || count > 1e6) {
    return failed(ActionStatus::InvalidArgument, fmt::format("wait: {} is not a whole number of steps", count));
  }
  RobotActionResult r;
  r.steps = static_cast<int>(count);
  return r;
}

RobotActionResult RobotActions::grasp(world::World& w, const std::string& body, ExecutionMode mode) const {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() >= 0) return failed(ActionStatus::AlreadyHolding, ws.state().held->object);
  if (!ws.objectPose(body)) return failed(ActionStatus::InvalidArgument, fmt::format("no movable object '{}'", body));
  Restore restore(w);
  RobotActionResult r;
  double reach = 0.15;  // builtins::grasp's default: the body's origin near the finger tip
  if (const auto approach = standardGraspTool(w, body)) {
    // Already at one of the body's standard grasps (a plan moved the arm there): grasp there.
    bool atGrasp = false;
    for (int k = 0; k < standardGraspCount(body) && !atGrasp; ++k)
      atGrasp = posesClose(ws.toolPose(), *standardGraspTool(w, body, k), 0.01, 0.1);
    if (!atGrasp) {
      ActionResult moved = moveToolIn(w, *approach, mode);
      if (!moved.done()) return failed(moved.status, "approaching the grasp of " + body + ": " + moved.detail);
      r.armPath = std::move(moved.armPath);
    }
    reach = 1.0;  // the grasp point is the standard one, not the body's origin
  }
  ActionResult attach = world::builtins::grasp(w, body, reach);
  if (!attach.done()) return failed(attach.status, attach.detail);
  world::Pose3 lifted = ws.toolPose();
  lifted.position.z() += kLift;
  // The body leaves the surface it rested on: the lift starts in contact with it.
  const ScopedAllowances leaving(w, restingContacts(w));
  ActionResult lift = moveToolIn(w, lifted, mode);
  if (!lift.done()) return failed(lift.status, "lifting " + body + ": " + lift.detail);
  r.armPath.insert(r.armPath.end(), lift.armPath.begin(), lift.armPath.end());
  restore.commit();
  return r;
}

RobotActionResult RobotActions::closeGripper(world::World& w, double closure) const {
  world::Workspace& ws = w.workspace();
  const world::WorldState before = ws.state();
  world::WorldState st = before;
  st.gripper = 1.0 - closure;
  ws.setState(st);
  // The fingers may not close into anything: the world (contact is contact) or what they hold (beyond the pads'
  // compliance).
  const world::CollisionReport c = world::checkRobotCollisions(ws, w.planning.collision);
  std::string why = c.free() ? std::string() : c.describe();
  if (why.empty() && ws.heldObject() >= 0) {
    const world::GripperContact held = world::gripperContact(ws, ws.heldObject());
    if (held.separation < -world::kGraspCompliance)
      why = fmt::format("{} would sink {:.1f} mm into {} (the pads give {:.0f} mm)",
                        ws.scene().geomName(held.gripperGeom), -1000 * held.separation,
                        ws.scene().geomName(held.objectGeom), 1000 * world::kGraspCompliance);
  }
  if (!why.empty()) {
    ws.setState(before);
    return failed(ActionStatus::Blocked, "closeGripper: " + why);
  }
  return RobotActionResult{};
}

RobotActionResult RobotActions::handOver(world::World& w) const {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() < 0) return failed(ActionStatus::NotHolding, "nothing to hand over");
  // When the user takes the object the gripper opens where it is, and the arm then moves on from there: that
  // state must be free too (the object stays attached for the check; its contacts with the gripper never count).
  const world::WorldState holding = ws.state();
  world::WorldState open = holding;
  open.gripper = 1.0;
  world::CollisionReport opened;
  if (ws.setState(open) == world::StateStatus::Ok) opened = world::checkRobotCollisions(ws, w.planning.collision);
  ws.setState(holding);
  if (!opened.free())
    return failed(ActionStatus::Blocked, fmt::format("the gripper could not open to let go of {}: {}",
                                                     holding.held->object, opened.describe()));
  return from(world::builtins::say(w, "Here you go!"));
}

RobotActionResult RobotActions::release(world::World& w) const {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() < 0) return failed(ActionStatus::NotHolding, "");
  const std::string body = ws.state().held->object;
  const world::Pose3 pose = *ws.objectPose(body);
  const auto extent = objectExtent(w, body, pose);
  // The highest surface under the body within the drop height catches it.
  std::optional<SurfaceFace> landing;
  for (const std::string& s : restingSurfaces(ws.scene())) {
    const auto face = surfaceFace(ws, s);
    const double gap = extent->bottom() - face->top();
    if (gap < -kRestBelow || gap > kDropHeight) continue;
    if (!face->containsXY(extent->center.x(), extent->center.y())) continue;
    if (!landing || face->top() > landing->top()) landing = face;
  }
  world::Pose3 settled = pose;
  if (landing) {
    settled = settledOn(*extent, pose, *landing);
  } else {
    // No box surface: whatever stands under its footprint (a round table top), if it then stands supported.
    const auto drop = world::dropDistance(ws, body, pose, kDropHeight);
    if (!drop || *drop < -kRestBelow)
      return failed(ActionStatus::Blocked, fmt::format("{} would not land on a surface", body));
    settled.position.z() -= *drop;
    const world::SupportReport support = world::supportAt(ws, body, settled);
    if (!support.supported())
      return failed(ActionStatus::Blocked, fmt::format("{} would not stand on {} ({} of {} rays find nothing under it)",
                                                       body, support.support.empty() ? "anything" : support.support,
                                                       support.unsupportedRays, world::kSupportRays + 1));
  }
  Restore restore(w);
  world::builtins::release(w);
  ws.setObjectPose(body, settled);
  restore.commit();
  return RobotActionResult{};
}

RobotActionResult RobotActions::place(world::World& w, const std::string& surface, const world::Pose3& pose,
                                      ExecutionMode mode) const {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() < 0 || !ws.state().held) return failed(ActionStatus::NotHolding, "nothing to place");
  const world::Grasp held = *ws.state().held;
  const auto face = surfaceFace(ws, surface);
  if (!face) return failed(ActionStatus::InvalidArgument, fmt::format("no box surface '{}'", surface));
  if (!restsOn(w, held.object, pose, surface)) {
    return failed(ActionStatus::InvalidArgument,
                  fmt::format("{} at the requested pose does not rest on {}", held.object, surface));
  }
  const world::Pose3 settled = settledOn(*objectExtent(w, held.object, pose), pose, *face);
  world::PlacementOptions clear;
  clear.clearance = 0.0;
  const world::PlacementReport rep = w.clearance().checkPlacement(ws, held.object, settled, clear);
  if (!rep.ok()) {
    return failed(ActionStatus::Blocked,
                  fmt::format("{} would touch {} ({})", held.object, rep.other, world::toString(rep.status)));
  }
  Restore restore(w);
  RobotActionResult r;
  const world::Pose3 tool = pose * held.toolToObject.inverse();
  if (!posesClose(ws.toolPose(), tool, 1e-3, 0.01)) {
    // The body comes to rest on the surface's face: that contact (and only that) is part of the motion.
    world::ContactAllowance onFace;
    onFace.geom = ws.scene().geomId(surface);
    onFace.separation = -kRestingContact;
    const ScopedAllowances resting(w, {onFace});
    ActionResult moved = moveToolIn(w, tool, mode);
    if (!moved.done()) return failed(moved.status, "carrying " + held.object + ": " + moved.detail);
    r.armPath = std::move(moved.armPath);
  }
  world::builtins::release(w);
  ws.setObjectPose(held.object, settled);
  const world::Pose3 here = ws.toolPose();
  const world::Pose3 back{here.position - kRetract * (here.orientation * Eigen::Vector3d::UnitZ()), here.orientation};
  ActionResult retract = moveToolIn(w, back, mode);
  if (!retract.done()) return failed(retract.status, "retracting from " + held.object + ": " + retract.detail);
  r.armPath.insert(r.armPath.end(), retract.armPath.begin(), retract.armPath.end());
  restore.commit();
  return r;
}

}  // namespace cbtl::actions
