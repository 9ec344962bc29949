// One of the two translation units that include FCL (slow to compile); Clearance.cpp is the other.
#include "robot/world/GeomDistance.h"

#include "robot/world/FclShapes.h"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

namespace cbtl::world {

namespace {

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Segment endpoints of a sphere (both at the centre) or a capsule (the centre ± half-length along the geom's z).
void axisEnds(const mjModel* m, const mjData* d, int g, double* a, double* b) {
  const double* c = d->geom_xpos + 3 * g;
  const double* r = d->geom_xmat + 9 * g;
  const double h = m->geom_type[g] == mjGEOM_CAPSULE ? m->geom_size[3 * g + 1] : 0.0;
  for (int k = 0; k < 3; ++k) {
    a[k] = c[k] + h * r[3 * k + 2];
    b[k] = c[k] - h * r[3 * k + 2];
  }
}

bool roundShape(int type) { return type == mjGEOM_SPHERE || type == mjGEOM_CAPSULE; }

}  // namespace

Eigen::Isometry3d geomWorldTransform(const mjData* d, int g) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const double* r = d->geom_xmat + 9 * g;
  Eigen::Matrix3d rot;
  rot << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  t.linear() = rot;
  t.translation() = Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  return t;
}

namespace {

// Parameters s, t in [0, 1] of the nearest points of segments [p0, p1] and [q0, q1] (the classic clamped
// solution of the 2x2 system).
void nearestParameters(const double* p0, const double* p1, const double* q0, const double* q1, double& s, double& t) {
  double d1[3], d2[3], r[3];
  for (int k = 0; k < 3; ++k) {
    d1[k] = p1[k] - p0[k];
    d2[k] = q1[k] - q0[k];
    r[k] = p0[k] - q0[k];
  }
  const double a = dot3(d1, d1), e = dot3(d2, d2), f = dot3(d2, r);
  constexpr double kTiny = 1e-18;
  s = t = 0;
  if (a <= kTiny && e <= kTiny) return;
  if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = dot3(d1, r);
  if (e <= kTiny) {
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = dot3(d1, d2);
  const double denom = a * e - b * b;
  s = denom > kTiny ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

}  // namespace

double segmentSegmentDistance(const double* p0, const double* p1, const double* q0, const double* q1) {
  double s = 0, t = 0;
  nearestParameters(p0, p1, q0, q1, s, t);
  double diff[3];
  for (int k = 0; k < 3; ++k) diff[k] = (p0[k] + s * (p1[k] - p0[k])) - (q0[k] + t * (q1[k] - q0[k]));
  return std::sqrt(dot3(diff, diff));
}

double pointBoxDistance(const double* x, const double* c, const double* r, const double* h) {
  const double v[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  double outside = 0, deepest = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double local = r[k] * v[0] + r[3 + k] * v[1] + r[6 + k] * v[2];  // v in the box's frame
    const double excess = std::abs(local) - h[k];
    if (excess > 0) outside += excess * excess;
    deepest = std::max(deepest, excess);
  }
  return outside > 0 ? std::sqrt(outside) : deepest;  // inside: minus the distance to the nearest face
}

namespace {

// A convex geom at its world pose, for support functions: h(u) = max over the solid of u·x.
struct Solid {
  int type = mjGEOM_BOX;
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns: the geom's x, y, z axes in the world frame
  Eigen::Vector3d size;  // MuJoCo's geom_size

  Solid(const mjModel* m, const mjData* d, int g)
      : type(m->geom_type[g]), centre(d->geom_xpos + 3 * g), size(m->geom_size + 3 * g) {
    const double* r = d->geom_xmat + 9 * g;
    axes << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  }

  // max over the solid of u·x (u a unit vector); +inf for a half-space unless u is its outward normal.
  double support(const Eigen::Vector3d& u) const {
    const double c = u.dot(centre);
    switch (type) {
      case mjGEOM_SPHERE:
        return c + size[0];
      case mjGEOM_CAPSULE:
        return c + size[1] * std::abs(u.dot(axes.col(2))) + size[0];
      case mjGEOM_CYLINDER: {
        const double along = u.dot(axes.col(2));
        return c + size[1] * std::abs(along) + size[0] * std::sqrt(std::max(0.0, 1.0 - along * along));
      }
      case mjGEOM_ELLIPSOID: {
        double sum = 0;
        for (int k = 0; k < 3; ++k) sum += std::pow(size[k] * u.dot(axes.col(k)), 2);
        return c + std::sqrt(sum);
      }
      case mjGEOM_PLANE: {
        const Eigen::Vector3d n = axes.col(2);
        return u.dot(n) > 1.0 - 1e-12 ? c : std::numeric_limits<double>::infinity();
      }
      default: {  // box
        double reach = 0;
        for (int k = 0; k < 3; ++k) reach += size[k] * std::abs(u.dot(axes.col(k)));
        return c + reach;
      }
    }
  }
};

// The point of `s` farthest along the unit vector d (a point where support(d) is reached), or nullopt for a shape
// without a closed form here (ellipsoid, plane).
std::optional<Eigen::Vector3d> supportPoint(const Solid& s, const Eigen::Vector3d& d) {
  const auto sign = [](double x) { return x < 0 ? -1.0 : 1.0; };
  switch (s.type) {
    case mjGEOM_SPHERE:
      return Eigen::Vector3d(s.centre + s.size[0] * d);
    case mjGEOM_CAPSULE:
      return Eigen::Vector3d(s.centre + s.size[1] * sign(d.dot(s.axes.col(2))) * s.axes.col(2) + s.size[0] * d);
    case mjGEOM_CYLINDER: {
      const Eigen::Vector3d z = s.axes.col(2);
      const Eigen::Vector3d radial = d - d.dot(z) * z;
      const double n = radial.norm();
      Eigen::Vector3d p = s.centre + s.size[1] * sign(d.dot(z)) * z;
      if (n > 1e-12) p += s.size[0] / n * radial;
      return p;
    }
    case mjGEOM_BOX: {
      Eigen::Vector3d p = s.centre;
      for (int k = 0; k < 3; ++k) p += s.size[k] * sign(d.dot(s.axes.col(k))) * s.axes.col(k);
      return p;
    }
    default:
      return std::nullopt;
  }
}

// The width of the empty slab between a and b across direction u (from a towards b): a lower bound on their
// distance for every u, and, when they overlap, at most minus their penetration depth. The true signed distance
// is the largest gap over all directions.
double gap(const Solid& a, const Solid& b, Eigen::Vector3d u) {
  const double n = u.norm();
  if (!(n > 1e-12)) return -std::numeric_limits<double>::infinity();
  u /= n;
  return -b.support(-u) - a.support(u);
}

// A plane's separation from a solid: exact (the solid's lowest point above the plane's surface).
double planeSeparation(const Solid& plane, const Solid& other) {
  const Eigen::Vector3d n = plane.axes.col(2);
  return -other.support(-n) - n.dot(plane.centre);
}

// The point of segment [p, q] nearest to the box `box` (golden-section search on the convex distance) and the box's
// point nearest to it: their difference is the direction across which a round solid on that segment and the box
// are farthest apart. Zero when the segment enters the box.
Eigen::Vector3d segmentBoxDirection(const Solid& box, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  // In the box's frame the box is [-size, size]: the distance of a point is that of its clamped copy.
  const Eigen::Vector3d lp = box.axes.transpose() * (p - box.centre);
  const Eigen::Vector3d lq = box.axes.transpose() * (q - box.centre);
  const Eigen::Vector3d h = box.size;
  auto offset = [&](double t) {
    const Eigen::Vector3d x = lp + t * (lq - lp);
    return Eigen::Vector3d(x - x.cwiseMax(-h).cwiseMin(h));
  };
  constexpr double kInvPhi = 0.6180339887498949;
  double lo = 0, hi = 1, x1 = hi - kInvPhi, x2 = kInvPhi;
  double f1 = offset(x1).squaredNorm(), f2 = offset(x2).squaredNorm();
  for (int i = 0; i < 30; ++i) {  // the bracket shrinks to 0.618^30 (1e-6) of the segment
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - kInvPhi * (hi - lo), f1 = offset(x1).squaredNorm();
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + kInvPhi * (hi - lo), f2 = offset(x2).squaredNorm();
    }
  }
  return box.axes * offset(0.5 * (lo + hi));  // from the box towards the segment, in the world frame
}

bool axial(const Solid& s) { return s.type == mjGEOM_SPHERE || s.type == mjGEOM_CAPSULE || s.type == mjGEOM_CYLINDER; }

// The separating-axis candidates, each in both senses (complete for two boxes: two boxes are apart exactly when one
// of these separates them, and the smallest overlap among them is their depth): each solid's axes (the face
// normals) to `face`, their cross products (edge against edge) to `edge`. The directions need not be unit length.
template <class Face, class Edge>
void visitSeparatingAxes(const Solid& a, const Solid& b, Face&& face, Edge&& edge) {
  for (int i = 0; i < 3; ++i)
    for (const Eigen::Vector3d& u : {Eigen::Vector3d(a.axes.col(i)), Eigen::Vector3d(b.axes.col(i))}) {
      face(u);
      face(-u);
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d c = a.axes.col(i).cross(b.axes.col(j));
      edge(c);
      edge(-c);
    }
}

// The widest slab across the separating-axis candidates; the edge directions only when the face normals leave the
// gap at or below `enough` (face normals decide most pairs: faces facing each other).
double axesGap(const Solid& a, const Solid& b, double enough) {
  double faces = -std::numeric_limits<double>::infinity(), edges = faces;
  visitSeparatingAxes(
      a, b, [&](const Eigen::Vector3d& u) { faces = std::max(faces, gap(a, b, u)); },
      [&](const Eigen::Vector3d& u) {
        if (!(faces > enough)) edges = std::max(edges, gap(a, b, u));
      });
  return std::max(faces, edges);
}

// axesGap for two boxes in closed form (the classic oriented-box test: B's axes in A's frame, R = AᵀB): the same
// slab widths gap() measures across the same 15 directions, for a fraction of the work. A cross axis of two nearly
// parallel edges (|a_i × b_j| < 1e-6) is skipped, since dividing by its length would magnify rounding; the face
// normals decide that case, and leaving out a candidate only lowers the bound (a deeper overlap, a smaller gap).
double boxAxesGap(const Solid& a, const Solid& b, double enough) {
  const Eigen::Matrix3d r = a.axes.transpose() * b.axes;
  const Eigen::Matrix3d absR = r.cwiseAbs();
  const Eigen::Vector3d d = a.axes.transpose() * (b.centre - a.centre);
  const Eigen::Vector3d& ha = a.size;
  const Eigen::Vector3d& hb = b.size;
  double best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) best = std::max(best, std::abs(d[i]) - ha[i] - absR.row(i).dot(hb));
  for (int j = 0; j < 3; ++j) best = std::max(best, std::abs(r.col(j).dot(d)) - absR.col(j).dot(ha) - hb[j]);
  if (best > enough) return best;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const double length = std::sqrt(std::max(0.0, 1.0 - r(i, j) * r(i, j)));
      if (length < 1e-6) continue;
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double across = std::abs(d[i2] * r(i1, j) - d[i1] * r(i2, j));
      const double reachA = ha[i1] * absR(i2, j) + ha[i2] * absR(i1, j);
      const double reachB = hb[j1] * absR(i, j2) + hb[j2] * absR(i, j1);
      best = std::max(best, (across - reachA - reachB) / length);
    }
  }
  return best;
}

// The gap across the direction in which a sphere, capsule or cylinder's axis comes nearest to a box (exact for a
// sphere or capsule apart from the box: the nearest points of its axis and the box give the witness direction).
// -inf when neither is such a pair or the axis enters the box.
double axisBoxGap(const Solid& a, const Solid& b) {
  for (const auto& [box, other, sign] : {std::tuple{&a, &b, 1.0}, std::tuple{&b, &a, -1.0}}) {
    if (box->type != mjGEOM_BOX || !axial(*other)) continue;
    const double h = other->type == mjGEOM_SPHERE ? 0.0 : other->size[1];
    const Eigen::Vector3d axis = other->axes.col(2);
    const Eigen::Vector3d u = segmentBoxDirection(*box, other->centre + h * axis, other->centre - h * axis);
    return std::max(gap(a, b, sign * u), gap(a, b, -sign * u));
  }
  return -std::numeric_limits<double>::infinity();
}

// The gap across the direction joining the nearest points of two sphere, capsule or cylinder axes (exact for two
// spheres or capsules; only a lower bound, possibly a poor one, when a cylinder is involved: cheapGap). -inf unless
// both are such solids.
double axisAxisGap(const Solid& a, const Solid& b) {
  if (!axial(a) || !axial(b)) return -std::numeric_limits<double>::infinity();
  auto ends = [](const Solid& x, Eigen::Vector3d& p, Eigen::Vector3d& q) {
    const double h = x.type == mjGEOM_SPHERE ? 0.0 : x.size[1];
    p = x.centre + h * x.axes.col(2);
    q = x.centre - h * x.axes.col(2);
  };
  Eigen::Vector3d p0, p1, q0, q1;
  ends(a, p0, p1);
  ends(b, q0, q1);
  double s = 0, t = 0;
  nearestParameters(p0.data(), p1.data(), q0.data(), q1.data(), s, t);
  const Eigen::Vector3d u = (q0 + t * (q1 - q0)) - (p0 + s * (p1 - p0));
  return std::max(gap(a, b, u), gap(a, b, -u));
}

// The gap across a cylinder's axis (a round table top and what is above it, a cup standing on it), and whether it is
// the distance: it is when the other solid's point nearest the cylinder's end plane lies over the end disc, since
// that point is then exactly the slab's width from a point of the disc. -inf (not exact) unless one is a cylinder.
double cylinderFaceGap(const Solid& a, const Solid& b, bool& exact) {
  exact = false;
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& [c, o, sense] : {std::tuple{&a, &b, 1.0}, std::tuple{&b, &a, -1.0}}) {
    if (c->type != mjGEOM_CYLINDER) continue;
    const Eigen::Vector3d axis = c->axes.col(2);
    const Eigen::Vector3d n = (o->centre - c->centre).dot(axis) < 0 ? Eigen::Vector3d(-axis) : axis;  // c towards o
    const double width = gap(a, b, sense * n);
    best = std::max(best, width);
    const auto p = supportPoint(*o, -n);
    if (width > 0 && p) {
      const Eigen::Vector3d off = *p - c->centre;
      exact = exact || (off - off.dot(axis) * axis).norm() <= c->size[0];
    }
  }
  return best;
}

// The cheap candidate directions, by pair kind, stopping as soon as a gap exceeds `enough`: the line between the
// centres; for a round solid (sphere, capsule, cylinder) and a box or another round solid, the nearest-point
// direction of their axes, taken as the answer when it shows them apart; the separating-axis candidates.
// `settled` tells the caller that an iterative method would not improve the answer much.
double cheapGap(const Solid& a, const Solid& b, double enough, bool& settled) {
  settled = false;
  double best = gap(a, b, b.centre - a.centre);
  if (best > enough) return best;
  if (axial(a) || axial(b)) {
    best = std::max({best, axisBoxGap(a, b), axisAxisGap(a, b)});
    // The axis direction is the witness only for spheres and capsules (every point within the radius of the axis). A
    // cylinder's rim reaches its radius out from the axis in its end planes, so for a wide flat one (a round table
    // top) the axis direction can be far from the witness: a box 16 cm above such a top measured 9 mm that way. The
    // other directions (its axis among the separating-axis candidates, FCL's) then decide.
    const bool witness = a.type != mjGEOM_CYLINDER && b.type != mjGEOM_CYLINDER;
    if (best > enough || (witness && best > 0)) {
      settled = witness && best > 0;
      return best;
    }
    bool exact = false;
    best = std::max(best, cylinderFaceGap(a, b, exact));
    if (exact || best > enough) {
      settled = exact;
      return best;
    }
  }
  const bool boxes = a.type == mjGEOM_BOX && b.type == mjGEOM_BOX;
  best = std::max(best, boxes ? boxAxesGap(a, b, enough) : axesGap(a, b, enough));
  // Two boxes: the separating-axis candidates decide overlap exactly and give its depth exactly; apart, their gap
  // is the distance for faces or edges facing each other (books on shelves, a gripper over a table) and a lower
  // bound otherwise, which the certificates can work with.
  settled = boxes;
  return best;
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> fclShapeOf(const mjModel* m, int g) {
  const mjtNum* s = m->geom_size + 3 * g;
  std::shared_ptr<fcl::CollisionGeometryd> shape;
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
      shape = std::make_shared<fcl::Boxd>(2 * s[0], 2 * s[1], 2 * s[2]);
      break;
    case mjGEOM_SPHERE:
      shape = std::make_shared<fcl::Sphered>(s[0]);
      break;
    case mjGEOM_CAPSULE:
      shape = std::make_shared<fcl::Capsuled>(s[0], 2 * s[1]);
      break;
    case mjGEOM_CYLINDER:
      shape = std::make_shared<fcl::Cylinderd>(s[0], 2 * s[1]);
      break;
    case mjGEOM_ELLIPSOID:
      shape = std::make_shared<fcl::Ellipsoidd>(s[0], s[1], s[2]);
      break;
    case mjGEOM_PLANE:
      shape = std::make_shared<fcl::Halfspaced>(Eigen::Vector3d::UnitZ(), 0.0);
      break;
    default:
      return nullptr;
  }
  shape->computeLocalAABB();
  return shape;
}

struct GeomDistance::Impl {
  const mjModel* model = nullptr;
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> shapes;  // null: unsupported type

  // FCL's GJK/EPA give only a direction, tried after the cheap ones: the answer is always a gap computed from
  // exact support functions, so a wrong FCL result can only make it more cautious. (FCL 0.7's GJK was seen to
  // report two boxes that overlap 0.4 mm as 2.3 mm apart.)
  double convexSeparation(const mjData* d, int g1, int g2, double enough, bool needDepth) const {
    const Solid a(model, d, g1), b(model, d, g2);
    if (a.type == mjGEOM_PLANE) return planeSeparation(a, b);
    if (b.type == mjGEOM_PLANE) return planeSeparation(b, a);
    bool settled = false;
    const double best = cheapGap(a, b, enough, settled);
    if (best > enough || settled) return best;
    const fcl::Transform3d t1 = geomWorldTransform(d, g1), t2 = geomWorldTransform(d, g2);
    const fcl::CollisionGeometryd* s1 = shapes[static_cast<size_t>(g1)].get();
    const fcl::CollisionGeometryd* s2 = shapes[static_cast<size_t>(g2)].get();
    fcl::DistanceRequestd dreq(true);
    dreq.gjk_solver_type = fcl::GST_INDEP;
    fcl::DistanceResultd dres;
    if (fcl::distance(s1, t1, s2, t2, dreq, dres) > 0) {
      const Eigen::Vector3d u = dres.nearest_points[1] - dres.nearest_points[0];
      return std::max({best, gap(a, b, u), gap(a, b, -u)});
    }
    if (!needDepth) return best;
    fcl::CollisionRequestd creq(1, true);
    creq.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd cres;
    fcl::collide(s1, t1, s2, t2, creq, cres);
    if (cres.numContacts() == 0) return best;
    const Eigen::Vector3d u = cres.getContact(0).normal;
    return std::max({best, gap(a, b, u), gap(a, b, -u)});
  }
};

double GeomDistance::translationSeparation(const mjData* d, int g1, int g2, const double v[3]) const {
  const Solid a(impl_->model, d, g1), b(impl_->model, d, g2);
  const Eigen::Vector3d shift(v[0], v[1], v[2]);
  double best = -std::numeric_limits<double>::infinity();
  // gap(a, b, u) is measured across u from a towards b: translating a by s·v raises a's support along u by s·(u·v).
  auto tryDirection = [&](Eigen::Vector3d u) {
    const double n = u.norm();
    if (!(n > 1e-12)) return;
    u /= n;
    best = std::max(best, gap(a, b, u) - std::max(0.0, u.dot(shift)));
  };
  visitSeparatingAxes(a, b, tryDirection, tryDirection);
  tryDirection(b.centre - a.centre);
  tryDirection(b.centre - a.centre - shift);
  return best;
}

GeomDistance::GeomDistance(const mjModel* m) : impl_(std::make_unique<Impl>()) {
  impl_->model = m;
  impl_->shapes.resize(static_cast<size_t>(m->ngeom));
  for (int g = 0; g < m->ngeom; ++g) {
    impl_->shapes[static_cast<size_t>(g)] = fclShapeOf(m, g);
  }
}

GeomDistance::~GeomDistance() = default;

bool GeomDistance::supports(int g) const { return impl_->shapes[static_cast<size_t>(g)] != nullptr; }

double GeomDistance::separation(const mjData* d, int g1, int g2, double enough, bool needDepth) const {
  const mjModel* m = impl_->model;
  const int t1 = m->geom_type[g1], t2 = m->geom_type[g2];
  if (roundShape(t1) && roundShape(t2)) {
    // Exact in closed form: the distance between the axes minus both radii (negative: the overlap depth).
    double a0[3], a1[3], b0[3], b1[3];
    axisEnds(m, d, g1, a0, a1);
    axisEnds(m, d, g2, b0, b1);
    return segmentSegmentDistance(a0, a1, b0, b1) - m->geom_size[3 * g1] - m->geom_size[3 * g2];
  }
  return impl_->convexSeparation(d, g1, g2, enough, needDepth);
}

}  // namespace cbtl::world
