#include "robot/world/SurfaceFace.h"

#include <cmath>

namespace cbtl::world {

bool SurfaceFace::containsXY(double x, double y, double margin) const {
  return std::abs(x - center.x()) <= halfX + margin && std::abs(y - center.y()) <= halfY + margin;
}

std::optional<SurfaceFace> surfaceFace(const Workspace& ws, std::string_view geom) {
  const int g = ws.scene().geomId(geom);
  if (g < 0 || ws.model()->geom_type[g] != mjGEOM_BOX) return std::nullopt;
  const mjtNum* size = ws.model()->geom_size + 3 * g;
  const mjtNum* rot = ws.data()->geom_xmat + 9 * g;
  const mjtNum* pos = ws.data()->geom_xpos + 3 * g;
  // Half-extent of the rotated box along world axis `row`: sum over its own axes of |R(row, axis)| * size.
  double h[3];
  for (int row = 0; row < 3; ++row) {
    h[row] =
        std::abs(rot[3 * row]) * size[0] + std::abs(rot[3 * row + 1]) * size[1] + std::abs(rot[3 * row + 2]) * size[2];
  }
  return SurfaceFace{Eigen::Vector3d(pos[0], pos[1], pos[2] + h[2]), h[0], h[1]};
}

}  // namespace cbtl::world
