#include "domains/feeding/FeedingActions.h"

#include "domains/feeding/TableSlide.h"
#include "robot/actions/CallArguments.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/MotionQuery.h"

#include <fmt/format.h>

#include <cmath>

namespace cbtl::domains::feeding {

namespace {

using world::Pose3;
using world::builtins::ActionStatus;

// The drink's handle in the drink's body frame (the holder box of feeding.xml), metres.
const Eigen::Vector3d kDrinkGraspOffset(-0.085, 0.0, 0.2);
// The utensil mount's grasp pose (feeding.cbtl mountX, mountY, mountLowZ), tool pointing down.
const Eigen::Vector3d kMountLow(0.242, -0.077, 0.07);
constexpr int kDrinkIkDraws = 5;  // IK draws from random starts behind the handle

Eigen::Quaterniond towardsPlusY() { return Eigen::Quaterniond(0.0, 0.0, 0.7071067811865476, 0.7071067811865476); }

actions::RobotActionResult failed(ActionStatus s, std::string detail) {
  actions::RobotActionResult r;
  r.status = s;
  r.detail = std::move(detail);
  return r;
}

actions::RobotActionResult illFormed(std::string detail) {
  actions::RobotActionResult r = failed(ActionStatus::InvalidArgument, std::move(detail));
  r.wellFormed = false;
  r.steps = 0;
  return r;
}

bool holding(const world::Workspace& ws, const char* object) {
  return ws.heldObject() >= 0 && ws.scene().objects()[static_cast<std::size_t>(ws.heldObject())].name == object;
}

// The arm configuration behind the handle that the approach moves to: of up to kDrinkIkDraws converged IK draws,
// the first that the straight joint segment from the current arm reaches certified free (planning clearances),
// else the first converged one (the approach then needs the planner). Preferring the straight segment matters: a
// dry run with no planner budget otherwise rejects every drink the first draw's elbow cannot reach without
// sweeping past the user's head, and the solver then moves the drink rather than plan around. Both execution
// modes choose alike (the check is pure), so the effects they leave agree. The arm is left where it was.
std::optional<world::ArmConfig> approachConfiguration(world::World& w, const Pose3& behind, world::Rng& rng) {
  world::Workspace& ws = w.workspace();
  const world::ArmConfig start = ws.state().arm;
  std::optional<world::ArmConfig> first;
  for (int draw = 0; draw < kDrinkIkDraws; ++draw) {
    const std::optional<world::ArmConfig> q = world::builtins::sampleIk(w, behind, rng);
    if (!q) continue;
    if (!first) first = q;
    const bool straight = world::armSegmentFree(ws, start, *q, w.planning.collision);
    ws.setArm(start);
    if (straight) return q;
  }
  return first;
}

}  // namespace

Pose3 drinkHandlePose(const Pose3& drink) {
  return Pose3{drink.transformPoint(kDrinkGraspOffset) - Eigen::Vector3d(0, kDrinkGraspStandoff, 0), towardsPlusY()};
}

Pose3 drinkInTool(const Pose3& drink) { return drinkHandlePose(drink).inverse() * drink; }

std::shared_ptr<const FeedingActions> FeedingActions::forScene(const world::Scene& scene) {
  const int index = scene.objectIndex("utensil");
  if (index < 0) return std::make_shared<const FeedingActions>(Pose3{});
  const mjtNum* q = scene.model()->qpos0 + scene.objects()[static_cast<std::size_t>(index)].qposAdr;
  return std::make_shared<const FeedingActions>(
      Pose3{Eigen::Vector3d(q[0], q[1], q[2]), Eigen::Quaterniond(q[3], q[4], q[5], q[6])});
}

bool FeedingActions::handles(std::string_view name) const {
  return name == "movePlate" || name == "moveDrink" || name == "dipInto" || name == "acquireFood" ||
         name == "waitForReady";
}

std::optional<actions::RobotActionResult> FeedingActions::execute(world::World& w, const sim::ActionCall& call,
                                                                  actions::ExecutionMode mode) const {
  const std::string& n = call.name;
  if (isTableSlide(n)) return slideOnTable(w, call);
  if (n == "grasp" && call.args.size() == 1 && call.args[0].kind == sim::Value::Kind::Name &&
      call.args[0].text == "drink")
    return graspDrink(w, mode);
  if (n == "release" && call.args.empty() && holding(w.workspace(), "utensil")) return releaseUtensil(w);
  if (n == "acquireFood") {
    if (auto e = actions::checkArguments(call, {}); !e.empty()) return illFormed(e);
    return acquireFood(w);
  }
  if (n == "dipInto" || n == "waitForReady") {
    if (auto e = actions::checkArguments(call, {actions::kNameArg}); !e.empty()) return illFormed(e);
    return actions::RobotActionResult{};
  }
  return std::nullopt;
}

actions::RobotActionResult FeedingActions::graspDrink(world::World& w, actions::ExecutionMode mode) const {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() >= 0) return failed(ActionStatus::AlreadyHolding, "grasp(drink): the gripper is not empty");
  const auto drink = ws.objectPose("drink");
  if (!drink) return failed(ActionStatus::InvalidArgument, "no movable object 'drink'");
  const Pose3 handle = drinkHandlePose(*drink);
  Pose3 behind = handle;
  behind.position.y() -= kDrinkApproach;
  // IK from random starts (seeded at the folded arm, every converged solution reaches around the table); the
  // starts are drawn from a stream that is a function of the state and the handle.
  std::vector<double> key(ws.state().arm.begin(), ws.state().arm.end());
  key.insert(key.end(), {handle.position.x(), handle.position.y(), handle.position.z()});
  world::Rng rng(world::fingerprintOf(key));
  const std::optional<world::ArmConfig> q = approachConfiguration(w, behind, rng);
  if (!q) {
    return failed(ActionStatus::NoIk,
                  fmt::format("grasp(drink): no collision-free IK solution behind the handle of the drink at "
                              "({:.3f}, {:.3f})",
                              drink->position.x(), drink->position.y()));
  }
  const world::WorldState before = ws.state();
  const world::builtins::ActionResult approach = actions::moveArmIn(w, *q, mode);
  if (!approach.done()) return failed(approach.status, "grasp(drink): approach: " + approach.detail);
  // The open fingers slide along the handle's sides: a straight line, never a detour around it.
  const world::builtins::ActionResult in = actions::moveToolStraightIn(w, handle, mode);
  if (!in.done()) {
    ws.setState(before);
    return failed(in.status, "grasp(drink): onto the handle: " + in.detail);
  }
  const world::builtins::ActionResult closed = world::builtins::grasp(w, "drink", 1.0);
  if (!closed.done()) {
    ws.setState(before);
    return failed(closed.status, "grasp(drink): " + closed.detail);
  }
  Pose3 lifted = ws.toolPose();
  lifted.position.z() += kDrinkLift;
  // The lift starts with the drink on the table: that contact, and only that, is allowed, and the joint move up
  // is certified like every other motion.
  world::IkOptions liftIk = w.ik;
  for (const auto& a : actions::restingContacts(w)) liftIk.collision.allowances.push_back(a);
  const world::ArmConfig grasped = ws.state().arm;
  const world::IkResult up = world::solveIk(ws, lifted, grasped, rng, liftIk);
  ws.setArm(grasped);
  if (!up.solved()) {
    ws.setState(before);
    return failed(ActionStatus::NoIk, fmt::format("grasp(drink): lift: {}", world::toString(up.status)));
  }
  if (mode == actions::ExecutionMode::Execute && !world::armSegmentFree(ws, grasped, up.q, liftIk.collision)) {
    ws.setState(before);
    return failed(ActionStatus::NoPath, "grasp(drink): the lift is not certified free");
  }
  ws.setArm(up.q);
  if (mode == actions::ExecutionMode::Execute) w.noteArmMotion({grasped, up.q}, liftIk.collision);
  actions::RobotActionResult r;
  r.armPath = approach.armPath;
  r.armPath.insert(r.armPath.end(), in.armPath.begin() + (in.armPath.empty() ? 0 : 1), in.armPath.end());
  r.armPath.push_back(up.q);
  return r;
}

actions::RobotActionResult FeedingActions::releaseUtensil(world::World& w) const {
  world::Workspace& ws = w.workspace();
  if ((ws.toolPose().position - kMountLow).norm() > kMountTolerance)
    return failed(ActionStatus::OutOfReach, "release(): the utensil is not at its mount");
  ws.setHeld(std::nullopt);
  ws.setObjectPose("utensil", mount_);
  world::WorldState s = ws.state();
  s.gripper = 1.0;
  ws.setState(s);
  return {};
}

actions::RobotActionResult FeedingActions::acquireFood(world::World& w) const {
  world::Workspace& ws = w.workspace();
  const auto plate = ws.objectPose("plate");
  const auto tip = ws.sitePose("utensil_tip");
  if (!holding(ws, "utensil") || !plate || !tip ||
      std::hypot(tip->position.x() - plate->position.x(), tip->position.y() - plate->position.y()) > kFoodReach)
    return failed(ActionStatus::OutOfReach, "acquireFood(): the fork is not above the food");
  return {};
}

}  // namespace cbtl::domains::feeding
