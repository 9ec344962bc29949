// WipeSweep.h — std.actions' wipe(surface, base): sweeping the held duster over a surface by moving the
// mobile base with the arm fixed (the reference's wiping motion), and the pre-wipe pose a sweep starts from.
//
// Pre-wipe pose: world/PreWipe.h preWipeToolPose.
//
// Sweep (sweepSurface), given the robot holds an object whose bottom lies within [-kContactBelow,
// +kContactAbove] of the face top and whose origin lies over the face grown by kContactReach:
//   1. if the base is not at `base` (1 mm / 1 mrad), plan the base there (arm fixed);
//   2. the tool moves straight down (world/CartesianPath.h) until the held object's lowest point is kWipePress
//      into the face (exact separations), so that the duster touches what it wipes; after step 4 it moves
//      straight back up to where it began;
//   3. strokes along the face's longer side, ceil(width / kStrokeSpacing) of them evenly spread across the
//      shorter side, each covering kStrokeCoverage of the length; boustrophedon order starting with the
//      stroke and end nearest to the object's start position; the object's height never changes;
//   4. the base translates by the same offsets as the object (yaw kept) and finally returns to `base`;
//      every straight base segment is certified free along its whole length (world/SegmentCertificate.h) for
//      the robot and the held object with the scene's clearances: the duster touches the face it wipes only where
//      the skill declares it (`allow held touch surfaceGeom[s] 5 mm { wipe(...); }` in cleaning.cbtl).
// Failures (the world is left as it was): NotHolding; InvalidArgument (no box surface of that name); Blocked (the
// call's exceptions do not let the held object touch the face kWipeAllowanceNeeded deep: the message says what to
// declare); OutOfReach (the held object is not on the surface); NoPath (base planning to `base`, the press or the lift,
// or a sweep segment collides: the detail names the geoms).
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
// Metres the held object's lowest point is aimed into the face for the strokes. IK stops within 1 mm of its target
// (coming from above), so it ends about 1-3 mm in: touching, and inside cleaning.cbtl's 5 mm allowance.
inline constexpr double kWipePress = 0.002;
// The contact depth the skill must allow between the held object and the face (Blocked otherwise): the press plus
// the IK's 1 mm.
inline constexpr double kWipeAllowanceNeeded = kWipePress + 0.001;

// The pre-wipe pose lives in the world library (world/PreWipe.h), where std.collision's wipeStartPose reads it.
using world::preWipeToolPose;

// The sweep described above (the base is planned to `base` with world::builtins::moveBase).
// `effectsOnly` (an executor's Effects mode: a dry run's end state): the press follows the same IK chain without its
// collision checks and the strokes are not certified (the checks decide acceptance, not the configurations), so it
// ends where a checked sweep does; only an executed sweep is certified.
world::builtins::ActionResult sweepSurface(world::World& w, const std::string& surface, const world::Pose2& base,
                                           bool effectsOnly = false);

}  // namespace cbtl::actions
