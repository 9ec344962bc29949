#include "robot/world/RobotDistance.h"

#include "robot/world/Separation.h"

#include <algorithm>

namespace cbtl::world {

RobotDistance robotDistanceTo(Workspace& ws, const std::vector<int>& bodies, double cap,
                              const CollisionOptions& options) {
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  const Scene& s = ws.scene();
  const int held = ws.heldObject();
  RobotDistance nearest{cap, {}, {}, 0.0, cap, {}, {}};
  for (int g1 = 0; g1 < m->ngeom; ++g1) {
    const int b1 = m->geom_bodyid[g1];
    const BodyKind k1 = s.bodyKind(b1);
    const bool moving = k1 == BodyKind::Robot || k1 == BodyKind::Gripper || (held >= 0 && s.objectOfBody(b1) == held);
    if (!moving) continue;
    for (int g2 = 0; g2 < m->ngeom; ++g2) {
      if (std::find(bodies.begin(), bodies.end(), m->geom_bodyid[g2]) == bodies.end()) continue;
      if (lowerBound(m, d, g1, g2) >= cap) continue;  // farther than the cap: not measured
      const double dist = exactSeparation(ws, g1, g2);
      if (dist >= cap) continue;
      const double keepOut = requiredSeparation(ws, options, g1, g2);
      if (dist < nearest.distance) {
        nearest.distance = dist;
        nearest.robotGeom = s.geomName(g1);
        nearest.bodyGeom = s.geomName(g2);
        nearest.keepOut = keepOut;
      }
      if (dist - keepOut < nearest.slack) {
        nearest.slack = dist - keepOut;
        nearest.slackRobotGeom = s.geomName(g1);
        nearest.slackBodyGeom = s.geomName(g2);
      }
    }
  }
  return nearest;
}

}  // namespace cbtl::world
