// WipeSweep.h — std.actions' wipe(surface, base): sweeping the held duster over a surface by moving the
// mobile base with the arm fixed (the reference's wiping motion), and the pre-wipe pose a sweep starts from.
//
// Pre-wipe pose: world/PreWipe.h preWipeToolPose.
//
// Sweep (sweepSurface), given the robot holds an object whose bottom lies within [-kContactBelow,
// +kContactAbove] of the face top and whose origin lies over the face grown by kContactReach:
//   1. if the base is not at `base` (1 mm / 1 mrad), plan the base there (arm fixed);
//   2. strokes along the face's longer side, ceil(width / kStrokeSpacing) of them evenly spread across the
//      shorter side, each covering kStrokeCoverage of the length; boustrophedon order starting with the
//      stroke and end nearest to the object's start position; the object's height never changes;
//   3. the base translates by the same offsets as the object (yaw kept) and finally returns to `base`;
//      every straight base segment is certified free along its whole length (world/SegmentCertificate.h) for
//      the robot and the held object with the scene's clearances: the duster touches the face it wipes only where
//      the skill declares it (`allow held touch surfaceGeom[s] 5 mm { wipe(...); }` in cleaning.cbtl).
// Failures (the world is left as it was): NotHolding; InvalidArgument (no box surface of that name);
// OutOfReach (the held object is not on the surface); NoPath (base planning to `base`, or a sweep segment
// collides: the detail names the geoms).
#pragma once

#include "robot/world/PreWipe.h"
#include "robot/world/WorldOperations.h"

#include <optional>
#include <string>

namespace cbtl::actions {

inline constexpr double kStrokeSpacing = 0.15;  // metres between strokes (the duster head's length)
inline constexpr double kStrokeCoverage = 0.8;  // share of the face length a stroke covers
inline constexpr double kContactBelow = 0.01;   // the held object's bottom may be this far into the face...
inline constexpr double kContactAbove = 0.03;   // ...or this far above it
inline constexpr double kContactReach = 0.1;    // its origin may lie this far outside the face (x, y)

// The pre-wipe pose lives in the world library (world/PreWipe.h), where std.collision's wipeStartPose reads it.
using world::preWipeToolPose;

// The sweep described above (the base is planned to `base` with world::builtins::moveBase).
world::builtins::ActionResult sweepSurface(world::World& w, const std::string& surface, const world::Pose2& base);

}  // namespace cbtl::actions
