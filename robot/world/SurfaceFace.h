// SurfaceFace.h — the top face of a box geom, the surface objects rest on and tools wipe.
//
// A surface is a box geom; its usable part is the top face of its world-axis-aligned bounding box (for a
// box rotated about z the face is the AABB's, a conservative simplification). Frames: world; units: metres.
#pragma once

#include "robot/world/Workspace.h"

#include <Eigen/Core>

#include <optional>
#include <string_view>

namespace cbtl::world {

struct SurfaceFace {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // centre of the top face
  double halfX = 0, halfY = 0;                       // half-extents of the face along world x and y
  double top() const { return center.z(); }
  // Whether (x, y) lies on the face grown by `margin` metres on every side.
  bool containsXY(double x, double y, double margin = 0) const;
};

// The top face of box geom `geom` at the Workspace's current state; nullopt for an unknown or non-box geom.
std::optional<SurfaceFace> surfaceFace(const Workspace& ws, std::string_view geom);

}  // namespace cbtl::world
