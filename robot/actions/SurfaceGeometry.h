// SurfaceGeometry.h — surfaces objects rest on, and where objects rest, in a robot scene.
//
// A surface is a box geom; its usable part is the top face of its world-axis-aligned bounding box. An object's
// extent is the world-axis-aligned box around its geoms (ClearanceChecker::objectBox moved to its pose).
// Frames: world; units: metres.
#pragma once

#include "robot/world/SurfaceFace.h"

#include "robot/world/WorldOperations.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::actions {

// Surfaces' top faces: world/SurfaceFace.h.
using world::SurfaceFace;
using world::surfaceFace;

// The geoms of `scene` that objects may rest on: box geoms named "*_top" or "shelf_layer_*" (the home scene's
// convention, home.xml). In scene order.
std::vector<std::string> restingSurfaces(const world::Scene& scene);

struct ObjectExtent {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  double bottom() const { return center.z() - half.z(); }
};

// World-axis-aligned extent of `object` placed at `pose`; nullopt for an unknown object.
std::optional<ObjectExtent> objectExtent(const world::World& w, std::string_view object, const world::Pose3& pose);

// How far above a face (metres) an object's bottom may float, and how far it may sink in, and still count as
// resting on it (std.collision's restsOn: "bottom on the top face (1 cm)"); how far its footprint may overhang.
inline constexpr double kRestAbove = 0.01;
inline constexpr double kRestBelow = 0.002;
inline constexpr double kFootprintSlack = 0.002;

// Whether `object` at `pose` rests on `geom`: bottom within [top - kRestBelow, top + kRestAbove] and the
// footprint inside the face (kFootprintSlack). False for unknown names.
bool restsOn(const world::World& w, std::string_view object, const world::Pose3& pose, std::string_view geom);

// The first of `surfaces` that `object` (at its current pose) rests on, or nullopt.
std::optional<std::string> supportOf(const world::World& w, std::string_view object,
                                     const std::vector<std::string>& surfaces);

// `pose` moved along world z so that the object's bottom lies exactly on `face`.
world::Pose3 settledOn(const ObjectExtent& extent, const world::Pose3& pose, const SurfaceFace& face);

}  // namespace cbtl::actions
