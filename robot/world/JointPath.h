// JointPath.h — paths in a joint space whose coordinates are either bounded reals or angles (circular,
// wrapped to [-pi, pi)): interpolation, fine-resolution segment checking and shortcutting.
//
// Distances between waypoints are L∞ (the largest per-coordinate change, angles taken the short way
// round), so a `resolution` of 0.005 means no coordinate moves more than 0.005 (rad or m) between two
// checked states. Validity callbacks are called from the caller's thread only.
#pragma once

#include "robot/world/Pose.h"

#include <functional>
#include <vector>

namespace cbtl::world {

using Waypoint = std::vector<double>;
using ValidityFn = std::function<bool(const Waypoint&)>;

struct JointSpace {
  std::vector<bool> circular;  // per coordinate
  std::size_t size() const { return circular.size(); }
};

double linfDistance(const JointSpace& space, const Waypoint& a, const Waypoint& b);
// Sum over coordinates of |b - a| (angles the short way): the path length reported by planners.
double l1Distance(const JointSpace& space, const Waypoint& a, const Waypoint& b);
Waypoint interpolate(const JointSpace& space, const Waypoint& a, const Waypoint& b, double t);

// Checks b and every interior state of the segment a→b at spacing <= resolution, coarse-to-fine
// (bisection order) so that blocked segments fail early. `a` is assumed valid. Adds to *checks.
bool segmentValid(const JointSpace& space, const Waypoint& a, const Waypoint& b, double resolution,
                  const ValidityFn& valid, long* checks = nullptr);

// Shortens a valid path in place: a greedy pass that skips waypoints whose neighbours connect directly,
// then `attempts` random shortcuts between points on the path (drawn from rng), then a final greedy pass.
// Every accepted shortcut is checked with segmentValid at `resolution`, so the result stays valid.
void shortcutPath(const JointSpace& space, std::vector<Waypoint>& path, double resolution, const ValidityFn& valid,
                  int attempts, Rng& rng, long* checks = nullptr);

}  // namespace cbtl::world
