// FclShapes.h — the FCL shape of an MJCF geom (box, sphere, capsule, cylinder, ellipsoid; a plane as the solid
// half-space below it), in the geom's own frame, with its local bounding box computed. The one place that maps MuJoCo
// geom sizes to FCL's conventions (FCL boxes take full sizes, capsules and cylinders their full length).
//
// FCL is only forward-declared here: its headers are slow to compile, and only the .cpp files that call FCL include
// them (GeomDistance.cpp, Clearance.cpp).
#pragma once

#include <mujoco/mujoco.h>
#include <Eigen/Geometry>

#include <memory>

namespace fcl {
template <typename S>
class CollisionGeometry;
}  // namespace fcl

namespace cbtl::world {

// Null for meshes and height fields (no scene uses them).
std::shared_ptr<fcl::CollisionGeometry<double>> fclShapeOf(const mjModel* m, int g);

// The world pose of geom g in `d` (geom_xpos, geom_xmat), as FCL takes it (fcl::Transform3d is this type).
Eigen::Isometry3d geomWorldTransform(const mjData* d, int g);

}  // namespace cbtl::world
