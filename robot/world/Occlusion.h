// Occlusion.h — how much the robot (and anything else) blocks the user's view.
//
// Model (after the reference feeding environment): a gridSize x gridSize grid of ray origins with spacing
// `gridSpacing`, centred on the eye site, in the eye frame's x-y plane; parallel rays along the eye frame's
// +z (the gaze) of length `maxRayLength`. A ray hitting at grid offset (r, c) and distance d along the gaze
// scores exp(-alpha (r² + c²) / d²); a miss, or a hit at d ≈ 0, scores 0. The score is the mean over all
// rays, in [0, 1]. Rays ignore geoms outside groups 0 and 1 (visual-only geoms: the user's head, the
// utensil) and every geom of `excludeBody` (the user's head body).
// Units: metres. Frames: the eye site's frame (z = gaze) in world coordinates.
#pragma once

#include "robot/world/Workspace.h"

#include <string>

namespace cbtl::world {

struct OcclusionSpec {
  int eyeSite = -1;      // site whose z axis is the gaze
  int excludeBody = -1;  // body never hit by the rays (-1: none)
  int gridSize = 5;
  double gridSpacing = 0.1;    // m
  double maxRayLength = 10.0;  // m
  double alpha = 1.0;
};

// The feeding scene's spec: site user_eyes, body user_head excluded. Empty optional if the scene has no
// site named `eyeSite`.
std::optional<OcclusionSpec> occlusionSpecFor(const Scene& scene, const std::string& eyeSite = "user_eyes",
                                              const std::string& headBody = "user_head");

enum class RayMethod {
  // Geoms whose bounding sphere misses the ray bundle are culled once per call; the rest are intersected
  // with MuJoCo's per-geom ray functions. Same hits as mj_ray.
  Culled,
  // One mj_ray over all geoms per ray (the reference).
  MujocoRay,
};

// Score at the Workspace's current state.
double occlusionScore(const Workspace& ws, const OcclusionSpec& spec, RayMethod method = RayMethod::Culled);

}  // namespace cbtl::world
