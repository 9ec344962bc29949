#include "robot/actions/WipeSweep.h"

#include "robot/world/CartesianPath.h"
#include "robot/world/SegmentCertificate.h"
#include "robot/world/Separation.h"

#include "robot/actions/SurfaceGeometry.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace cbtl::actions {

using world::builtins::ActionResult;
using world::builtins::ActionStatus;

namespace {

ActionResult fail(ActionStatus s, std::string detail) {
  ActionResult r;
  r.status = s;
  r.detail = std::move(detail);
  return r;
}

bool sameBase(const world::Pose2& a, const world::Pose2& b) {
  return std::abs(a.x - b.x) <= 1e-3 && std::abs(a.y - b.y) <= 1e-3 && std::abs(world::angleDiff(a.yaw, b.yaw)) <= 1e-3;
}

// The object-origin waypoints (x, y) of the boustrophedon over `face`, starting near `start`.
std::vector<Eigen::Vector2d> strokeWaypoints(const SurfaceFace& face, const Eigen::Vector2d& start) {
  const bool alongX = face.halfX >= face.halfY;
  const double halfLength = alongX ? face.halfX : face.halfY;
  const double width = 2 * (alongX ? face.halfY : face.halfX);
  const int strokes = std::max(1, static_cast<int>(std::ceil(width / kStrokeSpacing - 1e-9)));
  const Eigen::Vector2d centre(face.center.x(), face.center.y());
  const double startAlong = alongX ? start.x() - centre.x() : start.y() - centre.y();
  const double startAcross = alongX ? start.y() - centre.y() : start.x() - centre.x();
  const auto across = [&](int k) { return -width / 2 + width * (k + 0.5) / strokes; };
  // Begin with the outer stroke nearer to the start, and at the stroke end nearer to it.
  const bool reverse = std::abs(across(strokes - 1) - startAcross) < std::abs(across(0) - startAcross);
  const double reach = halfLength * kStrokeCoverage;
  double along = startAlong <= 0 ? -reach : reach;
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < strokes; ++i) {
    const double a = across(reverse ? strokes - 1 - i : i);
    for (int end = 0; end < 2; ++end) {
      out.push_back(alongX ? centre + Eigen::Vector2d(along, a) : centre + Eigen::Vector2d(a, along));
      if (end == 0) along = -along;
    }
  }
  return out;
}

// The tool's straight path down onto box geom `surface` until the held object's lowest point is kWipePress into it
// (a duster that touches what it wipes: the pre-wipe pose leaves it hovering a few millimetres above), in
// ActionResult::armPath; the Workspace is left as it was. Blocked when the call's exceptions do not allow that
// contact, NoPath when no straight line keeps the separations they allow.
ActionResult pressOnto(world::World& w, const std::string& surface, bool effectsOnly) {
  world::Workspace& ws = w.workspace();
  const std::string held = ws.state().held->object;  // a copy: the line below resets the state
  const world::CollisionOptions& contact = w.planning.collision;
  const int faceGeom = ws.scene().geomId(surface);
  double height = std::numeric_limits<double>::infinity();
  int lowest = -1;
  for (int g = 0; g < ws.model()->ngeom; ++g)
    if (ws.scene().objectOfBody(ws.model()->geom_bodyid[g]) == ws.heldObject() &&
        (ws.model()->geom_contype[g] | ws.model()->geom_conaffinity[g]) != 0) {
      const double h = world::exactSeparation(ws, g, faceGeom);
      if (h < height) height = h, lowest = g;
    }
  // Touching the face is contact like any other: the call must carry the skill's exception for it.
  const double allowed = world::requiredSeparation(ws, contact, lowest, faceGeom);
  if (allowed > -kWipeAllowanceNeeded) {
    return fail(ActionStatus::Blocked,
                fmt::format("the sweep presses {} onto {} ({:.0f} mm in), a contact no `allow` of the skill declares "
                            "(e.g. `allow held touch \"{}\" 5 mm {{ wipe(...); }}`; it allows {:.1f} mm)",
                            held, surface, 1000 * kWipePress, surface, std::max(0.0, -1000 * allowed)));
  }
  world::Pose3 pressed = ws.toolPose();
  pressed.position.z() -= height + kWipePress;
  world::CartesianPathOptions line;
  line.collision = contact;
  line.maxStep = 0.002;  // short steps: the redundant arm's IK then stays near the previous configuration
  line.checkCollisions = !effectsOnly;
  auto down = world::cartesianToolPath(ws, pressed, w.ik, line);
  if (!down) {
    return fail(ActionStatus::NoPath,
                fmt::format("pressing {} onto {}: no straight line down keeps the separations the skill allows", held,
                            surface));
  }
  ActionResult r;
  r.armPath = std::move(*down);
  return r;
}

}  // namespace

ActionResult sweepSurface(world::World& w, const std::string& surface, const world::Pose2& base, bool effectsOnly) {
  world::Workspace& ws = w.workspace();
  if (ws.heldObject() < 0 || !ws.state().held) return fail(ActionStatus::NotHolding, "wiping needs a held duster");
  const auto face = surfaceFace(ws, surface);
  if (!face) return fail(ActionStatus::InvalidArgument, fmt::format("no box surface '{}'", surface));
  const world::WorldState saved = ws.state();
  const std::string held = saved.held->object;

  ActionResult r;
  if (!sameBase(ws.state().base, base)) {
    ActionResult toBase = world::builtins::moveBase(w, base);
    if (!toBase.done()) return fail(toBase.status, "reaching the wipe base: " + toBase.detail);
    r.basePath = std::move(toBase.basePath);
  }
  // Where the held object is, relative to the face.
  const world::Pose3 start = *ws.objectPose(held);
  const auto extent = objectExtent(w, held, start);
  const double gap = extent->bottom() - face->top();
  if (gap < -kContactBelow || gap > kContactAbove ||
      !face->containsXY(start.position.x(), start.position.y(), kContactReach)) {
    ws.setState(saved);
    return fail(ActionStatus::OutOfReach,
                fmt::format("{} is not on {} (bottom {:+.3f} m from the face, at ({:.3f}, {:.3f}))", held, surface, gap,
                            start.position.x(), start.position.y()));
  }
  const Eigen::Vector2d s(start.position.x(), start.position.y());
  std::vector<Eigen::Vector2d> targets = strokeWaypoints(*face, s);
  targets.push_back(s);  // back to where the sweep began, i.e. the base back at `base`

  // Contact with the face wiped, like any other, only as far as the skill declares it (`allow held touch ...`).
  const world::CollisionOptions& contact = w.planning.collision;
  ActionResult down = pressOnto(w, surface, effectsOnly);
  if (!down.done()) {
    ws.setState(saved);
    return down;
  }
  ws.setArm(down.armPath.back());
  w.noteArmMotion(down.armPath, contact);
  r.armPath = down.armPath;
  Eigen::Vector2d from = s;
  for (const Eigen::Vector2d& to : targets) {
    const world::Pose2 a{base.x + (from - s).x(), base.y + (from - s).y(), base.yaw};
    const world::Pose2 b{base.x + (to - s).x(), base.y + (to - s).y(), base.yaw};
    const world::SegmentReport c = effectsOnly ? world::SegmentReport{} : world::certifyBaseSegment(ws, a, b, contact);
    if (!c.free()) {
      ws.setState(saved);
      return fail(ActionStatus::NoPath,
                  fmt::format("the sweep over {} {}: {} ({}) with {}, {:.4f} m inside its separation", surface,
                              world::toString(c.status), c.contact.first, world::toString(c.contact.status),
                              c.contact.second, c.contact.depth));
    }
    ws.setBase(b);
    w.noteBaseMotion({a, b}, contact);
    r.basePath.push_back(b);
    from = to;
  }
  ws.setBase(base);
  // And up again the way it came: the world is the one the way down was certified in (the base is back at `base`).
  const std::vector<world::ArmConfig> up(down.armPath.rbegin(), down.armPath.rend());
  ws.setArm(up.back());
  w.noteArmMotion(up, contact);
  r.armPath.insert(r.armPath.end(), up.begin() + 1, up.end());
  return r;
}

}  // namespace cbtl::actions
