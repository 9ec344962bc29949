// Clearance.h — distances and placement checks between movable objects and the scenery, computed with FCL
// (MuJoCo 2.2.2 has no distance query). Shapes are generated from the scene's MJCF geoms (box, sphere,
// capsule, cylinder, ellipsoid, plane), so the MJCF is the single source of geometry. Visual-only geoms
// (contype = conaffinity = 0) and robot geoms are ignored.
//
// Thread safety: a ClearanceChecker holds only immutable FCL shapes after construction, but create one per
// thread anyway (it keeps scratch space). Units: metres; poses are object body frames in world coordinates.
// FCL distance uses the GST_INDEP solver (the default libccd solver is wrong in degenerate cases).
#pragma once

#include "robot/world/Workspace.h"

#include <memory>
#include <string>
#include <string_view>

namespace cbtl::world {

enum class PlacementStatus {
  Ok,
  UnknownObject,  // the object (or the other object) is not a movable object of the scene
  Collides,       // intersects scenery or another object even when lifted by the contact tolerance
  TooClose,       // closer than the required clearance to another movable object
};

const char* toString(PlacementStatus s);

struct PlacementReport {
  PlacementStatus status = PlacementStatus::Ok;
  std::string other;      // the geom (Collides) or object (TooClose) responsible; empty when Ok
  double distance = 0.0;  // its distance (TooClose) or penetration depth (Collides), metres
  bool ok() const { return status == PlacementStatus::Ok; }
};

struct PlacementOptions {
  double clearance = 0.1;  // minimum distance to every other movable object
  // The object is tested against scenery and objects lifted by this much (m), so resting on a surface or
  // sinking into it by less than this is not a collision.
  double contactTolerance = 1e-3;
};

class ClearanceChecker {
 public:
  explicit ClearanceChecker(std::shared_ptr<const Scene> scene);
  ~ClearanceChecker();
  ClearanceChecker(const ClearanceChecker&) = delete;
  ClearanceChecker& operator=(const ClearanceChecker&) = delete;

  // Distance between two movable objects placed at the given poses; 0 when they overlap.
  // Returns a negative value if either name is unknown.
  double objectDistance(std::string_view a, const Pose3& poseA, std::string_view b, const Pose3& poseB) const;

  // Whether `object` placed at `pose` is clear of the scenery (no penetration beyond the tolerance) and
  // at least `clearance` away from every other movable object at its pose in `ws` (the object itself and
  // the held object, if different, are skipped; the robot is ignored).
  PlacementReport checkPlacement(const Workspace& ws, std::string_view object, const Pose3& pose,
                                 const PlacementOptions& options = {}) const;

  // Axis-aligned half-extents and centre of an object's geoms in its own body frame.
  struct LocalBox {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();
  };
  std::optional<LocalBox> objectBox(std::string_view object) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cbtl::world
