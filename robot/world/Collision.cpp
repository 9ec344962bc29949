#include "robot/world/Collision.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

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

namespace {

bool isRobot(BodyKind k) { return k == BodyKind::Robot || k == BodyKind::Gripper; }

// Which failure a contact between bodies b1 and b2 represents, or Free if it does not count.
CollisionStatus classify(const Scene& s, int held, int b1, int b2) {
  const bool h1 = held >= 0 && s.objectOfBody(b1) == held;
  const bool h2 = held >= 0 && s.objectOfBody(b2) == held;
  const BodyKind k1 = s.bodyKind(b1), k2 = s.bodyKind(b2);
  if (h1 || h2) {
    if (h1 && h2) return CollisionStatus::Free;
    const BodyKind other = h1 ? k2 : k1;
    return other == BodyKind::Gripper ? CollisionStatus::Free : CollisionStatus::HeldObject;
  }
  if (isRobot(k1) && isRobot(k2)) return CollisionStatus::SelfCollision;
  if (isRobot(k1) || isRobot(k2)) return CollisionStatus::RobotWorld;
  return CollisionStatus::Free;
}

}  // namespace

namespace {

// Whether geom `g` (a box or a plane) is farther than `reach` from the point `x`: exact for the box's volume and
// the plane's solid half-space, so a sphere of radius `reach` around x cannot touch it.
bool beyond(const mjModel* m, const mjData* d, int g, const mjtNum* x, mjtNum reach) {
  const mjtNum* c = d->geom_xpos + 3 * g;
  const mjtNum* r = d->geom_xmat + 9 * g;  // row-major; columns are the geom's axes in the world frame
  const mjtNum v[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  if (m->geom_type[g] == mjGEOM_PLANE) return r[2] * v[0] + r[5] * v[1] + r[8] * v[2] > reach;
  const mjtNum* h = m->geom_size + 3 * g;
  mjtNum outside = 0;
  for (int k = 0; k < 3; ++k) {
    const mjtNum local = r[k] * v[0] + r[3 + k] * v[1] + r[6 + k] * v[2];  // v in the box's frame
    const mjtNum excess = std::abs(local) - h[k];
    if (excess > 0) outside += excess * excess;
  }
  return outside > reach * reach;
}

// Runs MuJoCo's narrow phase on one candidate pair; returns the deepest penetration (positive), or 0.
double pairPenetration(const mjModel* m, const mjData* d, const Scene::GeomPair& p, mjContact* buf) {
  const int g1 = p.g1, g2 = p.g2;
  const mjtNum r1 = m->geom_rbound[g1], r2 = m->geom_rbound[g2];
  const mjtNum margin = p.margin;
  // Planes have rbound 0 (unbounded): skip the sphere test for them, as MuJoCo does.
  if (r1 > 0 && r2 > 0) {
    const mjtNum* x1 = d->geom_xpos + 3 * g1;
    const mjtNum* x2 = d->geom_xpos + 3 * g2;
    const mjtNum dx = x1[0] - x2[0], dy = x1[1] - x2[1], dz = x1[2] - x2[2];
    const mjtNum reach = r1 + r2 + margin;
    if (dx * dx + dy * dy + dz * dz > reach * reach) return 0.0;
  }
  // Large boxes (walls, tables, shelves) and planes pass the sphere test for every nearby geom: test the other
  // geom's bounding sphere against their true extent before the narrow phase (a cheap, exact reject).
  for (const auto& [box, other] : {std::pair{g1, g2}, std::pair{g2, g1}}) {
    const int type = m->geom_type[box];
    if ((type == mjGEOM_BOX || type == mjGEOM_PLANE) && m->geom_rbound[other] > 0 &&
        beyond(m, d, box, d->geom_xpos + 3 * other, m->geom_rbound[other] + margin))
      return 0.0;
  }
  const mjfCollision fn = mjCOLLISIONFUNC[m->geom_type[g1]][m->geom_type[g2]];
  if (!fn) return 0.0;
  const int n = fn(m, d, buf, g1, g2, margin);
  double deepest = 0.0;
  for (int i = 0; i < n; ++i) deepest = std::max(deepest, margin - buf[i].dist);  // a margin keeps the robot out
  return deepest;
}

// A sphere around everything that moves with the robot (its links and the held object), for the broad phase:
// a geom whose bounding sphere misses it cannot touch the robot. Planes (rbound 0) never miss it.
struct MovingBound {
  mjtNum centre[3] = {0, 0, 0};
  mjtNum radius = 0;
};

void growBound(const mjModel* m, const mjData* d, const Scene& s, const std::vector<int>& geoms, MovingBound& b) {
  for (int g : geoms) {
    const mjtNum* x = d->geom_xpos + 3 * g;
    const mjtNum dx = x[0] - b.centre[0], dy = x[1] - b.centre[1], dz = x[2] - b.centre[2];
    b.radius = std::max(b.radius, std::sqrt(dx * dx + dy * dy + dz * dz) + m->geom_rbound[g] + s.reachMargin(g));
  }
}

MovingBound movingBound(const mjModel* m, const mjData* d, const Scene& s, int held) {
  // Centred on the middle of the moving geoms' centres' box, which keeps the sphere tight for an arm that
  // reaches out to one side.
  mjtNum lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  auto extend = [&](int g) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], d->geom_xpos[3 * g + k]);
      hi[k] = std::max(hi[k], d->geom_xpos[3 * g + k]);
    }
  };
  for (int g : s.robotGeoms()) extend(g);
  if (held >= 0)
    for (int g : s.objectSubtree(held).geoms()) extend(g);
  MovingBound b;
  for (int k = 0; k < 3; ++k) b.centre[k] = 0.5 * (lo[k] + hi[k]);
  growBound(m, d, s, s.robotGeoms(), b);
  if (held >= 0) growBound(m, d, s, s.objectSubtree(held).geoms(), b);
  return b;
}

// near[g]: geom g's bounding sphere (grown by its margin) reaches the moving bound.
void markNear(const mjModel* m, const mjData* d, const Scene& s, const MovingBound& b, std::vector<char>& near) {
  near.assign(static_cast<size_t>(m->ngeom), 1);
  for (int g = 0; g < m->ngeom; ++g) {
    const mjtNum r = m->geom_rbound[g];
    if (r <= 0) continue;
    const mjtNum* x = d->geom_xpos + 3 * g;
    const mjtNum dx = x[0] - b.centre[0], dy = x[1] - b.centre[1], dz = x[2] - b.centre[2];
    const mjtNum reach = b.radius + r + s.reachMargin(g);
    near[static_cast<size_t>(g)] = dx * dx + dy * dy + dz * dz <= reach * reach;
  }
}

CollisionReport checkPairs(Workspace& ws, const CollisionOptions& options) {
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  const Scene& s = ws.scene();
  thread_local std::vector<mjContact> buf(mjMAXCONPAIR);
  thread_local std::vector<char> near;
  const int held = ws.heldObject();
  auto report = [&](CollisionStatus st, const Scene::GeomPair& p, double depth) {
    return CollisionReport{st, s.geomName(p.g1), s.geomName(p.g2), depth};
  };
  // Broad phase: a pair is visited only when both of its geoms reach the moving bound (the robot side
  // always does). Pairs are still visited in the scene's order, so the first contact reported is unchanged.
  markNear(m, d, s, movingBound(m, d, s, held), near);
  auto bothNear = [&](const Scene::GeomPair& p) {
    return near[static_cast<size_t>(p.g1)] && near[static_cast<size_t>(p.g2)];
  };
  for (const auto& p : s.robotPairs()) {
    if (!bothNear(p)) continue;
    CollisionStatus st = CollisionStatus::RobotWorld;
    if (held >= 0) {
      const int b1 = m->geom_bodyid[p.g1], b2 = m->geom_bodyid[p.g2];
      st = classify(s, held, b1, b2);
      if (st == CollisionStatus::Free) continue;
    }
    const double depth = pairPenetration(m, d, p, buf.data());
    if (depth > options.tolerance) return report(st, p, depth);
  }
  for (const auto& p : s.selfPairs()) {
    const double depth = pairPenetration(m, d, p, buf.data());
    if (depth > options.tolerance) return report(CollisionStatus::SelfCollision, p, depth);
  }
  if (held >= 0) {
    for (const auto& p : s.objectPairs(held)) {
      if (!bothNear(p)) continue;
      const double depth = pairPenetration(m, d, p, buf.data());
      if (depth > options.tolerance) return report(CollisionStatus::HeldObject, p, depth);
    }
  }
  return {};
}

}  // namespace

CollisionReport checkRobotCollisions(Workspace& ws, const CollisionOptions& options) {
  if (options.method == CollisionMethod::RobotPairs) return checkPairs(ws, options);
  const mjModel* m = ws.model();
  mjData* d = ws.data();
  mj_collision(m, d);
  const Scene& s = ws.scene();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const double depth = c.includemargin - c.dist;  // includemargin = margin - gap: the pair's keep-out distance
    if (depth <= options.tolerance) continue;
    const CollisionStatus st = classify(s, ws.heldObject(), m->geom_bodyid[c.geom1], m->geom_bodyid[c.geom2]);
    if (st == CollisionStatus::Free) continue;
    return {st, s.geomName(c.geom1), s.geomName(c.geom2), depth};
  }
  return {};
}

CollisionReport checkArm(Workspace& ws, const ArmConfig& q, const CollisionOptions& options) {
  ws.setArm(q);
  return checkRobotCollisions(ws, options);
}

}  // namespace cbtl::world
