// Support.h — whether something holds a movable object up where it would stand: "the plate is on the table".
//
// Model: the object's footprint is the horizontal bounding rectangle of its lowest geoms (those whose bottom lies
// within kFootprintBand of the object's lowest point) at the pose asked about. Rays go straight down from the
// footprint's centre and from kSupportRays points on the ellipse inscribed in that rectangle (a round footprint's
// rim), starting kRayStartAbove over the object's lowest point; the object is supported when every ray meets a
// geom of group 0 (scenery, fixtures, other objects; not the robot, not visual-only geoms) no farther below the
// lowest point than kSupportGap. So a plate whose rim hangs over a round table's edge is not supported, whatever
// shape the table has: the check asks the scene's geometry, not a list of surfaces.
// The rays read the workspace's current state (fixtures and other objects where it put them); the object's own
// body is excluded. Frames: world; units: metres.
#pragma once

#include "robot/world/Workspace.h"

#include <optional>
#include <string>
#include <string_view>

namespace cbtl::world {

inline constexpr int kSupportRays = 16;
inline constexpr double kFootprintBand = 0.005;
inline constexpr double kRayStartAbove = 0.005;
inline constexpr double kSupportGap = 0.01;

enum class SupportStatus {
  Supported,
  UnknownObject,  // not a movable object of the scene, or the pose is not finite
  Overhangs,      // some of the footprint has nothing under it within kSupportGap
};

struct SupportReport {
  SupportStatus status = SupportStatus::Supported;
  std::string support;  // the geom under the footprint's centre (empty if none)
  int unsupportedRays = 0;
  bool supported() const { return status == SupportStatus::Supported; }
};

// Whether `object` placed at `pose` would stand supported in `ws`'s current state.
SupportReport supportAt(const Workspace& ws, std::string_view object, const Pose3& pose);

// How far `object` at `pose` would fall straight down before its footprint (the same rays) meets something:
// metres, the smallest over the rays (negative, down to -kRayStartAbove, when it already sinks in); nullopt when
// no ray meets anything within `maxDrop` or the object is unknown. A released object comes to rest there.
std::optional<double> dropDistance(const Workspace& ws, std::string_view object, const Pose3& pose, double maxDrop);

}  // namespace cbtl::world
