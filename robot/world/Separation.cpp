#include "robot/world/Separation.h"

#include "robot/world/GeomDistance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbtl::world {

namespace {

bool isRobot(BodyKind k) { return k == BodyKind::Robot || k == BodyKind::Gripper; }

// Which check a contact between bodies b1 and b2 belongs to, or Free when it is not checked.
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

// Whether geom g belongs to the moving part an allowance names.
bool isPart(const Scene& s, int held, int g, ContactAllowance::Part part) {
  const int b = s.model()->geom_bodyid[g];
  switch (part) {
    case ContactAllowance::Part::HeldObject:
      return held >= 0 && s.objectOfBody(b) == held;
    case ContactAllowance::Part::Gripper:
      return s.bodyKind(b) == BodyKind::Gripper;
    case ContactAllowance::Part::Robot:
      return isRobot(s.bodyKind(b));
  }
  return false;
}

bool names(const Scene& s, const ContactAllowance& a, int g) {
  return g == a.geom || (a.geom < 0 && a.body >= 0 && s.model()->geom_bodyid[g] == a.body);
}

// The separation the pair (g1, g2) must keep: its keep-out, or the smallest separation an allowance that covers it
// grants; at or above zero, at least kContactDistance.
double requiredSeparation(const Scene& s, int held, const CollisionOptions& o, int g1, int g2, double keepOut) {
  double required = keepOut;
  for (const ContactAllowance& a : o.allowances) {
    const bool covers =
        (isPart(s, held, g1, a.part) && names(s, a, g2)) || (isPart(s, held, g2, a.part) && names(s, a, g1));
    if (covers) required = std::min(required, a.separation);
  }
  return required >= 0 ? std::max(required, kContactDistance) : required;
}

// Puts the moving geom first (the held object's geom, or the robot's).
CheckedPair oriented(const Scene& s, int held, int g1, int g2, double required, CollisionStatus kind) {
  const mjModel* m = s.model();
  auto moving = [&](int g) {
    const int b = m->geom_bodyid[g];
    return isRobot(s.bodyKind(b)) || (held >= 0 && s.objectOfBody(b) == held);
  };
  if (!moving(g1) && moving(g2)) std::swap(g1, g2);
  return CheckedPair{g1, g2, required, kind};
}

struct PairCache {
  std::uint64_t scene = 0;
  int held = -2;
  CollisionOptions options;
  std::vector<CheckedPair> pairs;
};

void build(const Workspace& ws, const CollisionOptions& o, std::vector<CheckedPair>& out) {
  const Scene& s = ws.scene();
  const mjModel* m = s.model();
  const int held = ws.heldObject();
  out.clear();
  for (const auto& p : s.robotPairs()) {
    CollisionStatus kind = CollisionStatus::RobotWorld;
    if (held >= 0) {
      kind = classify(s, held, m->geom_bodyid[p.g1], m->geom_bodyid[p.g2]);
      if (kind == CollisionStatus::Free) continue;
    }
    out.push_back(oriented(s, held, p.g1, p.g2, requiredSeparation(s, held, o, p.g1, p.g2, p.margin), kind));
  }
  for (const auto& p : s.selfPairs())
    out.push_back(oriented(s, held, p.g1, p.g2, requiredSeparation(s, held, o, p.g1, p.g2, p.margin),
                           CollisionStatus::SelfCollision));
  if (held >= 0)
    for (const auto& p : s.objectPairs(held))
      out.push_back(oriented(s, held, p.g1, p.g2, requiredSeparation(s, held, o, p.g1, p.g2, p.margin),
                             CollisionStatus::HeldObject));
}

}  // namespace

double requiredSeparation(const Workspace& ws, const CollisionOptions& options, int g1, int g2) {
  const Scene& s = ws.scene();
  return requiredSeparation(s, ws.heldObject(), options, g1, g2, s.keepOut(g1, g2));
}

const std::vector<CheckedPair>& pairsFor(const Workspace& ws, const CollisionOptions& options) {
  thread_local PairCache cache;
  const Scene& s = ws.scene();
  if (cache.scene != s.serial() || cache.held != ws.heldObject() || !(cache.options == options)) {
    build(ws, options, cache.pairs);
    cache.scene = s.serial();
    cache.held = ws.heldObject();
    cache.options = options;
  }
  return cache.pairs;
}

double lowerBound(const mjModel* m, const mjData* d, int g1, int g2) {
  const double r1 = m->geom_rbound[g1], r2 = m->geom_rbound[g2];
  const double* x1 = d->geom_xpos + 3 * g1;
  const double* x2 = d->geom_xpos + 3 * g2;
  double bound = -std::numeric_limits<double>::infinity();
  // Planes have rbound 0 (unbounded): no sphere for them.
  if (r1 > 0 && r2 > 0) {
    const double dx = x1[0] - x2[0], dy = x1[1] - x2[1], dz = x1[2] - x2[2];
    bound = std::sqrt(dx * dx + dy * dy + dz * dz) - r1 - r2;
  }
  // A box or plane's true extent against the other geom's bounding sphere.
  for (const auto& [solid, other, otherRadius] : {std::tuple{g1, g2, r2}, std::tuple{g2, g1, r1}}) {
    if (otherRadius <= 0) continue;
    const int type = m->geom_type[solid];
    const double* c = d->geom_xpos + 3 * solid;
    const double* r = d->geom_xmat + 9 * solid;
    const double* x = d->geom_xpos + 3 * other;
    if (type == mjGEOM_BOX) {
      bound = std::max(bound, pointBoxDistance(x, c, r, m->geom_size + 3 * solid) - otherRadius);
    } else if (type == mjGEOM_PLANE) {
      const double height = r[2] * (x[0] - c[0]) + r[5] * (x[1] - c[1]) + r[8] * (x[2] - c[2]);
      bound = std::max(bound, height - otherRadius);
    }
  }
  return bound;
}

double exactSeparation(const Workspace& ws, int g1, int g2, double enough, bool needDepth) {
  const GeomDistance& exact = ws.scene().geomDistance();
  if (!exact.supports(g1) || !exact.supports(g2)) return lowerBound(ws.model(), ws.data(), g1, g2);
  return exact.separation(ws.data(), g1, g2, enough, needDepth);
}

const CheckedPair* firstViolation(const Workspace& ws, const std::vector<CheckedPair>& pairs, double* slack) {
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  for (const CheckedPair& p : pairs) {
    if (lowerBound(m, d, p.g1, p.g2) > p.required) continue;
    // Only an allowed contact needs its depth to decide; a violation is measured again for the report.
    const double sep = exactSeparation(ws, p.g1, p.g2, p.required, p.required < 0);
    if (sep <= p.required) {
      if (slack) *slack = exactSeparation(ws, p.g1, p.g2) - p.required;
      return &p;
    }
  }
  return nullptr;
}

}  // namespace cbtl::world
