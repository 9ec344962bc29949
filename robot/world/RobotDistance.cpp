#include "robot/world/RobotDistance.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>

namespace cbtl::world {

RobotDistance robotDistanceTo(Workspace& ws, const std::vector<int>& bodies, double cap) {
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  const Scene& s = ws.scene();
  const int held = ws.heldObject();
  RobotDistance nearest{cap, {}, {}, 0.0, cap, {}, {}};
  std::array<mjContact, mjMAXCONPAIR> buf{};
  for (int g1 = 0; g1 < m->ngeom; ++g1) {
    const int b1 = m->geom_bodyid[g1];
    const BodyKind k1 = s.bodyKind(b1);
    const bool moving = k1 == BodyKind::Robot || k1 == BodyKind::Gripper || (held >= 0 && s.objectOfBody(b1) == held);
    if (!moving) continue;
    for (int g2 = 0; g2 < m->ngeom; ++g2) {
      if (std::find(bodies.begin(), bodies.end(), m->geom_bodyid[g2]) == bodies.end()) continue;
      // MuJoCo's table holds each pair of types once, the lower type first.
      const bool swap = m->geom_type[g1] > m->geom_type[g2];
      const int a = swap ? g2 : g1, b = swap ? g1 : g2;
      const mjfCollision fn = mjCOLLISIONFUNC[m->geom_type[a]][m->geom_type[b]];
      if (!fn) continue;
      const int n = fn(m, d, buf.data(), a, b, cap);
      const double keepOut = s.keepOut(g1, g2);
      for (int i = 0; i < n; ++i) {
        const double dist = buf[static_cast<std::size_t>(i)].dist;
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
  }
  return nearest;
}

}  // namespace cbtl::world
