#include "robot/world/Occlusion.h"

#include <cmath>
#include <vector>

namespace cbtl::world {

std::optional<OcclusionSpec> occlusionSpecFor(const Scene& scene, const std::string& eyeSite,
                                              const std::string& headBody) {
  OcclusionSpec spec;
  spec.eyeSite = scene.siteId(eyeSite);
  if (spec.eyeSite < 0) return std::nullopt;
  spec.excludeBody = scene.bodyId(headBody);
  return spec;
}

namespace {

// The geoms mj_ray would consider (groups 0 and 1, visible, not on the excluded body) whose bounding sphere
// can touch a ray of the bundle: within the grid's half-width (plus radius) of the gaze axis, not behind.
void candidateGeoms(const mjModel* m, const mjData* d, const OcclusionSpec& spec, const Eigen::Vector3d& origin,
                    const Eigen::Matrix3d& R, double halfWidth, std::vector<int>& out) {
  out.clear();
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_group[g] < 0 || m->geom_group[g] > 1) continue;
    if (m->geom_bodyid[g] == spec.excludeBody) continue;
    const int mat = m->geom_matid[g];
    const float alpha = mat >= 0 ? m->mat_rgba[4 * mat + 3] : m->geom_rgba[4 * g + 3];
    if (alpha == 0) continue;
    const double r = m->geom_rbound[g];
    if (r > 0) {
      const Eigen::Vector3d c =
          R.transpose() *
          (Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]) - origin);
      if (std::abs(c.x()) > halfWidth + r || std::abs(c.y()) > halfWidth + r || c.z() < -r ||
          c.z() > spec.maxRayLength + r)
        continue;
    }
    out.push_back(g);
  }
}

// Nearest hit distance (in units of |vec|) of one ray against the candidate geoms, or -1.
mjtNum castAmong(const mjModel* m, const mjData* d, const std::vector<int>& geoms, const mjtNum pnt[3],
                 const mjtNum vec[3]) {
  mjtNum best = -1;
  for (int g : geoms) {
    mjtNum x;
    switch (m->geom_type[g]) {
      case mjGEOM_MESH:
        x = mj_rayMesh(m, d, g, pnt, vec);
        break;
      case mjGEOM_HFIELD:
        x = mj_rayHfield(m, d, g, pnt, vec);
        break;
      default:
        x = mju_rayGeom(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g, m->geom_size + 3 * g, pnt, vec, m->geom_type[g]);
    }
    if (x >= 0 && (best < 0 || x < best)) best = x;
  }
  return best;
}

}  // namespace

double occlusionScore(const Workspace& ws, const OcclusionSpec& spec, RayMethod method) {
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  const Pose3 eye = ws.sitePose(spec.eyeSite);
  const Eigen::Matrix3d R = eye.orientation.toRotationMatrix();
  const Eigen::Vector3d gaze = R.col(2);  // unit length, so mj_ray returns metres
  static const mjtByte kGroups[mjNGROUP] = {1, 1, 0, 0, 0, 0};
  const mjtNum vec[3] = {gaze.x() * spec.maxRayLength, gaze.y() * spec.maxRayLength, gaze.z() * spec.maxRayLength};
  const int half = spec.gridSize / 2;
  const double offset = (spec.gridSize % 2 == 0) ? 0.5 : 0.0;
  thread_local std::vector<int> candidates;
  if (method == RayMethod::Culled)
    candidateGeoms(m, d, spec, eye.position, R, (half + offset) * spec.gridSpacing + 1e-9, candidates);
  double sum = 0.0;
  for (int i = 0; i < spec.gridSize; ++i) {
    for (int j = 0; j < spec.gridSize; ++j) {
      const double r = (i - half + offset) * spec.gridSpacing;
      const double c = (j - half + offset) * spec.gridSpacing;
      const Eigen::Vector3d origin = eye.position + r * R.col(0) + c * R.col(1);
      const mjtNum pnt[3] = {origin.x(), origin.y(), origin.z()};
      int geom = -1;
      // mj_ray returns the hit distance in units of |vec| (here maxRayLength), or -1 for a miss.
      const mjtNum t = method == RayMethod::Culled ? castAmong(m, d, candidates, pnt, vec)
                                                   : mj_ray(m, d, pnt, vec, kGroups, 1, spec.excludeBody, &geom);
      if (t < 0 || t > 1) continue;
      const double dist = t * spec.maxRayLength;
      if (dist < 1e-9) continue;
      sum += std::exp(-spec.alpha * (r * r + c * c) / (dist * dist));
    }
  }
  return sum / (spec.gridSize * spec.gridSize);
}

}  // namespace cbtl::world
