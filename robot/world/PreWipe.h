// PreWipe.h — the tool pose from which a wiping sweep of a surface starts (std.collision's wipeStartPose;
// the Cleaning domain's sweep starts from it).
//
// The held object stands upright, its bottom kPreWipeLift above the face, its origin (the duster's head
// centre) kPreWipeEdgeInset inside the face edge nearest to the base — along the world axis (x or y) that
// dominates the direction from the base to the face centre — and, across that axis, at the base's
// coordinate clamped kPreWipeSideInset inside the face; its yaw makes the body's +y point from the base
// towards the surface (a duster's pole points back at the robot). The tool pose is that object pose composed
// with the inverse of the grasp. Frames: world; units: metres and radians.
#pragma once

#include "robot/world/WorldOperations.h"

#include <optional>
#include <string>

namespace cbtl::world {

inline constexpr double kPreWipeLift = 0.005;      // bottom above the face at the pre-wipe pose
inline constexpr double kPreWipeEdgeInset = 0.05;  // origin inside the near edge (head half-depth + 1 cm)
inline constexpr double kPreWipeSideInset = 0.08;  // origin inside the side edges (head half-length + 5 mm)

// The tool pose from which a sweep of box geom `surface` starts, for a held object `object` grasped with
// `toolToObject` (the object's frame in the tool frame) and the base at `base`; nullopt for an unknown
// surface or object.
std::optional<Pose3> preWipeToolPose(const World& w, const std::string& surface, const std::string& object,
                                     const Pose3& toolToObject, const Pose2& base);

}  // namespace cbtl::world
