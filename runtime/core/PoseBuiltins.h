// PoseBuiltins.h — std.geometry's planar and rigid poses as built-ins (compose, inverse, relativePose,
// poseRpy, toolDownAbove, retarget, ... and the samplers pointInShell, se2Near, toolDownAboveSampler,
// toolDownWithPointAbove).
//
// Conventions: SE2 yaw about world z in radians, wrapped to [-pi, pi); SE3 orientations as unit quaternions
// (qx, qy, qz, qw) with qw >= 0 on output; roll-pitch-yaw about the fixed axes x, then y, then z. "Tool
// down" is the tool z axis along world -z: a half turn about x, then the yaw about world z.
#pragma once

#include "runtime/core/Builtins.h"

namespace cbtl::rt {

// Registers the functions and samplers above in `b` (Builtins::standard() calls it).
void addPoseBuiltins(Builtins& b);

}  // namespace cbtl::rt
