#include "robot/world/Support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace cbtl::world {

namespace {

// Half extents of geom g's bounding box in its own frame.
Eigen::Vector3d geomHalfExtents(const mjModel* m, int g) {
  const mjtNum* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
    case mjGEOM_ELLIPSOID:
      return {s[0], s[1], s[2]};
    case mjGEOM_SPHERE:
      return {s[0], s[0], s[0]};
    case mjGEOM_CYLINDER:
      return {s[0], s[0], s[1]};
    case mjGEOM_CAPSULE:
      return {s[0], s[0], s[1] + s[0]};
    default:
      return Eigen::Vector3d::Constant(m->geom_rbound[g]);
  }
}

Pose3 localPose(const mjtNum* pos, const mjtNum* quat) {
  return Pose3{Eigen::Vector3d(pos[0], pos[1], pos[2]), Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3])};
}

// Frame of body b in the frame of its object's root body `root` (b is root or one of its descendants).
Pose3 inRoot(const mjModel* m, int b, int root) {
  Pose3 p;
  while (b != root && b > 0) {
    p = localPose(m->body_pos + 3 * b, m->body_quat + 4 * b) * p;
    b = m->body_parentid[b];
  }
  return p;
}

struct GeomBox {
  Eigen::Vector3d lo, hi;  // world-axis-aligned bounds
};

// The footprint of object `index` at `pose`: its lowest point and the horizontal rectangle of its lowest geoms.
struct Footprint {
  double bottom = 0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero(), radii = Eigen::Vector2d::Zero();
  // Ray origin k of 0 .. kSupportRays: the centre, then the rim of the inscribed ellipse.
  Eigen::Vector2d point(int k) const {
    if (k == 0) return centre;
    const double a = 2 * std::numbers::pi * (k - 1) / kSupportRays;
    return centre + Eigen::Vector2d(radii.x() * std::cos(a), radii.y() * std::sin(a));
  }
};

std::optional<Footprint> footprintAt(const Scene& scene, int index, const Pose3& pose) {
  const mjModel* m = scene.model();
  const int root = scene.objects()[static_cast<std::size_t>(index)].body;
  std::vector<GeomBox> boxes;
  double bottom = std::numeric_limits<double>::infinity();
  for (int g = 0; g < m->ngeom; ++g) {
    if (scene.objectOfBody(m->geom_bodyid[g]) != index) continue;
    const Pose3 world =
        pose * inRoot(m, m->geom_bodyid[g], root) * localPose(m->geom_pos + 3 * g, m->geom_quat + 4 * g);
    const Eigen::Matrix3d r = world.orientation.normalized().toRotationMatrix();
    const Eigen::Vector3d half = r.cwiseAbs() * geomHalfExtents(m, g);
    boxes.push_back({world.position - half, world.position + half});
    bottom = std::min(bottom, world.position.z() - half.z());
  }
  if (boxes.empty()) return std::nullopt;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const GeomBox& b : boxes) {
    if (b.lo.z() > bottom + kFootprintBand) continue;
    lo = lo.cwiseMin(b.lo.head<2>());
    hi = hi.cwiseMax(b.hi.head<2>());
  }
  Footprint f;
  f.bottom = bottom;
  f.centre = (lo + hi) / 2;
  f.radii = (hi - lo) / 2;
  return f;
}

// Distance from (xy, fromZ) straight down to the first geom of group 0 not of body `exclude`; -1 for none.
double rayDown(const Workspace& ws, const Eigen::Vector2d& xy, double fromZ, int exclude, int* geom) {
  static constexpr mjtByte kGroups[mjNGROUP] = {1, 0, 0, 0, 0, 0};
  const mjtNum from[3] = {xy.x(), xy.y(), fromZ};
  const mjtNum down[3] = {0, 0, -1};
  return mj_ray(ws.model(), ws.data(), from, down, kGroups, 1, exclude, geom);
}

bool validPose(const Pose3& pose) { return pose.position.allFinite() && pose.orientation.coeffs().allFinite(); }

}  // namespace

SupportReport supportAt(const Workspace& ws, std::string_view object, const Pose3& pose) {
  SupportReport report;
  const Scene& scene = ws.scene();
  const int index = scene.objectIndex(object);
  if (index < 0 || !validPose(pose)) return {SupportStatus::UnknownObject, {}, 0};
  const auto f = footprintAt(scene, index, pose);
  if (!f) return {SupportStatus::UnknownObject, {}, 0};
  const int root = scene.objects()[static_cast<std::size_t>(index)].body;
  const double reach = kRayStartAbove + kSupportGap;
  for (int k = 0; k <= kSupportRays; ++k) {
    int geom = -1;
    const double d = rayDown(ws, f->point(k), f->bottom + kRayStartAbove, root, &geom);
    const bool hit = geom >= 0 && d >= 0 && d <= reach;
    if (k == 0 && hit) report.support = scene.geomName(geom);
    if (!hit) ++report.unsupportedRays;
  }
  if (report.unsupportedRays > 0) report.status = SupportStatus::Overhangs;
  return report;
}

std::optional<double> dropDistance(const Workspace& ws, std::string_view object, const Pose3& pose, double maxDrop) {
  const Scene& scene = ws.scene();
  const int index = scene.objectIndex(object);
  if (index < 0 || !validPose(pose)) return std::nullopt;
  const auto f = footprintAt(scene, index, pose);
  if (!f) return std::nullopt;
  const int root = scene.objects()[static_cast<std::size_t>(index)].body;
  std::optional<double> drop;
  for (int k = 0; k <= kSupportRays; ++k) {
    int geom = -1;
    const double d = rayDown(ws, f->point(k), f->bottom + kRayStartAbove, root, &geom);
    if (geom < 0 || d < 0 || d > kRayStartAbove + maxDrop) continue;
    if (!drop || d - kRayStartAbove < *drop) drop = d - kRayStartAbove;
  }
  return drop;
}

}  // namespace cbtl::world
