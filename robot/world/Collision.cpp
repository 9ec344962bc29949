#include "robot/world/Collision.h"

#include "robot/world/Separation.h"

#include <fmt/core.h>

namespace cbtl::world {

const char* toString(CollisionStatus s) {
  switch (s) {
    case CollisionStatus::Free:
      return "free";
    case CollisionStatus::RobotWorld:
      return "robot collides with the world";
    case CollisionStatus::SelfCollision:
      return "self-collision";
    case CollisionStatus::HeldObject:
      return "held object collides";
  }
  return "unknown";
}

const char* toString(ContactAllowance::Part part) {
  switch (part) {
    case ContactAllowance::Part::HeldObject:
      return "held";
    case ContactAllowance::Part::Gripper:
      return "gripper";
    case ContactAllowance::Part::Robot:
      return "robot";
  }
  return "?";
}

std::string CollisionReport::describe() const {
  if (free()) return "free";
  const double separation = required - depth;
  std::string text = separation <= 0 ? fmt::format("{} touches {} ({:.1f} mm deep", first, second, -separation * 1e3)
                                     : fmt::format("{} comes {:.1f} mm from {} (", first, separation * 1e3, second);
  if (!clearance.empty())
    text += fmt::format("{}clearance {} needs {:.1f} mm)", separation <= 0 ? "; " : "", clearance, required * 1e3);
  else if (required < 0)
    text += fmt::format("{}{:.1f} mm allowed)", separation <= 0 ? "; " : "", -required * 1e3);
  else if (required > kContactDistance)
    text += fmt::format("{}keep-out {:.1f} mm)", separation <= 0 ? "; " : "", required * 1e3);
  else if (separation > 0)
    text += fmt::format("within {:.3f} mm: contact)", kContactDistance * 1e3);
  else
    text += ")";
  return text;
}

CollisionReport checkRobotCollisions(Workspace& ws, const CollisionOptions& options) {
  double slack = 0;
  const CheckedPair* p = firstViolation(ws, pairsFor(ws, options), &slack);
  if (!p) return {};
  const Scene& s = ws.scene();
  CollisionReport r{p->kind, s.geomName(p->g1), s.geomName(p->g2), -slack, p->required, {}};
  const BodyClearance* c = s.clearanceOfBody(s.model()->geom_bodyid[p->g2]);
  if (c && p->required > 0 && p->required == c->distance)
    r.clearance =
        c->declaredAt.empty() ? fmt::format("'{}'", c->name) : fmt::format("'{}' ({})", c->name, c->declaredAt);
  return r;
}

CollisionReport checkArm(Workspace& ws, const ArmConfig& q, const CollisionOptions& options) {
  ws.setArm(q);
  return checkRobotCollisions(ws, options);
}

}  // namespace cbtl::world
