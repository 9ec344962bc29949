// JointPath.h — paths in a joint space whose coordinates are either bounded reals or angles (circular,
// wrapped to [-pi, pi)): distances, interpolation and shortcutting.
//
// Segments are straight lines in the space (angles taken the short way round); whether one is free is the
// caller's SegmentFn (the planners certify it whole: SegmentCertificate.h). Callbacks are called from the
// caller's thread only.
#pragma once

#include "robot/world/Pose.h"

#include <functional>
#include <vector>

namespace cbtl::world {

using Waypoint = std::vector<double>;
using ValidityFn = std::function<bool(const Waypoint&)>;
// Whether the straight segment a→b is free (both ends included).
using SegmentFn = std::function<bool(const Waypoint&, const Waypoint&)>;

struct JointSpace {
  std::vector<bool> circular;  // per coordinate
  std::size_t size() const { return circular.size(); }
};

double linfDistance(const JointSpace& space, const Waypoint& a, const Waypoint& b);
// Sum over coordinates of |b - a| (angles the short way): the path length reported by planners.
double l1Distance(const JointSpace& space, const Waypoint& a, const Waypoint& b);
Waypoint interpolate(const JointSpace& space, const Waypoint& a, const Waypoint& b, double t);

// Shortens a valid path in place: a greedy pass that skips waypoints whose neighbours connect directly,
// then `attempts` random shortcuts between points on the path (drawn from rng), then a final greedy pass.
// Every accepted shortcut is a segment `free` accepted, so the result stays valid.
void shortcutPath(const JointSpace& space, std::vector<Waypoint>& path, const SegmentFn& free, int attempts, Rng& rng);

}  // namespace cbtl::world
