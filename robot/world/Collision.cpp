#include "robot/world/Collision.h"

#include "robot/world/Separation.h"

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

CollisionReport checkRobotCollisions(Workspace& ws, const CollisionOptions& options) {
  double slack = 0;
  const CheckedPair* p = firstViolation(ws, pairsFor(ws, options), &slack);
  if (!p) return {};
  const Scene& s = ws.scene();
  return {p->kind, s.geomName(p->g1), s.geomName(p->g2), -slack};
}

CollisionReport checkArm(Workspace& ws, const ArmConfig& q, const CollisionOptions& options) {
  ws.setArm(q);
  return checkRobotCollisions(ws, options);
}

}  // namespace cbtl::world
