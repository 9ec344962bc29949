#include "domains/feeding/TableSlide.h"

#include "robot/actions/CallArguments.h"
#include "robot/world/Support.h"

#include <fmt/core.h>

#include <cmath>

namespace cbtl::domains::feeding {

namespace {

using world::builtins::ActionStatus;

actions::RobotActionResult failed(ActionStatus s, std::string detail) {
  actions::RobotActionResult r;
  r.status = s;
  r.detail = std::move(detail);
  return r;
}

}  // namespace

bool isTableSlide(const std::string& action) { return action == "movePlate" || action == "moveDrink"; }

actions::RobotActionResult slideOnTable(world::World& w, const sim::ActionCall& call) {
  if (auto e = actions::checkArguments(call, {actions::kVec2Arg}); !e.empty()) {
    actions::RobotActionResult r;
    r.wellFormed = false;
    r.status = ActionStatus::InvalidArgument;
    r.detail = std::move(e);
    r.steps = 0;
    return r;
  }
  const double x = call.args[0].vector[0], y = call.args[0].vector[1];
  if (!std::isfinite(x) || !std::isfinite(y))
    return failed(ActionStatus::InvalidArgument, call.name + ": the position is not finite");
  const std::string object = call.name == "movePlate" ? "plate" : "drink";
  world::Workspace& ws = w.workspace();
  auto pose = ws.objectPose(object);
  if (!pose) return failed(ActionStatus::InvalidArgument, fmt::format("no movable object '{}'", object));
  if (ws.scene().objectIndex(object) == ws.heldObject())
    return failed(ActionStatus::InvalidArgument, fmt::format("'{}' is held by the robot", object));
  pose->position.x() = x;
  pose->position.y() = y;
  world::PlacementOptions o;
  o.clearance = 0.0;
  const world::PlacementReport rep = w.clearance().checkPlacement(ws, object, *pose, o);
  if (!rep.ok()) return failed(ActionStatus::Blocked, fmt::format("{} would touch {}", object, rep.other));
  const world::SupportReport support = world::supportAt(ws, object, *pose);
  if (!support.supported())
    return failed(
        ActionStatus::Blocked,
        fmt::format("{} at ({:.3f}, {:.3f}) would not stand on the table ({} of {} rays find nothing under it)", object,
                    x, y, support.unsupportedRays, world::kSupportRays + 1));
  ws.setObjectPose(object, *pose);
  return {};
}

}  // namespace cbtl::domains::feeding
