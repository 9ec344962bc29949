#include "robot/actions/SurfaceGeometry.h"

#include <cmath>

namespace cbtl::actions {

std::vector<std::string> restingSurfaces(const world::Scene& scene) {
  std::vector<std::string> out;
  const mjModel* m = scene.model();
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_BOX) continue;
    const std::string name = scene.geomName(g);
    const bool top = name.size() > 4 && name.compare(name.size() - 4, 4, "_top") == 0;
    const bool layer = name.rfind("shelf_layer_", 0) == 0;
    if (top || layer) out.push_back(name);
  }
  return out;
}

std::optional<ObjectExtent> objectExtent(const world::World& w, std::string_view object, const world::Pose3& pose) {
  const auto box = w.clearance().objectBox(object);
  if (!box) return std::nullopt;
  const Eigen::Matrix3d r = pose.orientation.normalized().toRotationMatrix();
  ObjectExtent e;
  e.center = pose.position + r * box->center;
  e.half = r.cwiseAbs() * box->halfExtents;
  return e;
}

bool restsOn(const world::World& w, std::string_view object, const world::Pose3& pose, std::string_view geom) {
  const auto face = surfaceFace(w.workspace(), geom);
  const auto e = objectExtent(w, object, pose);
  if (!face || !e) return false;
  const double gap = e->bottom() - face->top();
  if (gap < -kRestBelow || gap > kRestAbove) return false;
  return std::abs(e->center.x() - face->center.x()) + e->half.x() <= face->halfX + kFootprintSlack &&
         std::abs(e->center.y() - face->center.y()) + e->half.y() <= face->halfY + kFootprintSlack;
}

std::optional<std::string> supportOf(const world::World& w, std::string_view object,
                                     const std::vector<std::string>& surfaces) {
  const auto pose = w.workspace().objectPose(object);
  if (!pose) return std::nullopt;
  for (const std::string& s : surfaces)
    if (restsOn(w, object, *pose, s)) return s;
  return std::nullopt;
}

world::Pose3 settledOn(const ObjectExtent& extent, const world::Pose3& pose, const SurfaceFace& face) {
  world::Pose3 p = pose;
  p.position.z() += face.top() - extent.bottom();
  return p;
}

}  // namespace cbtl::actions
