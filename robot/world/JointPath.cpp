#include "robot/world/JointPath.h"

#include <algorithm>
#include <cmath>

namespace cbtl::world {

namespace {
double coordDiff(bool circular, double to, double from) { return circular ? angleDiff(to, from) : to - from; }
}  // namespace

double linfDistance(const JointSpace& space, const Waypoint& a, const Waypoint& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < space.size(); ++i) d = std::max(d, std::abs(coordDiff(space.circular[i], b[i], a[i])));
  return d;
}

double l1Distance(const JointSpace& space, const Waypoint& a, const Waypoint& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < space.size(); ++i) d += std::abs(coordDiff(space.circular[i], b[i], a[i]));
  return d;
}

Waypoint interpolate(const JointSpace& space, const Waypoint& a, const Waypoint& b, double t) {
  Waypoint r(a.size());
  for (std::size_t i = 0; i < space.size(); ++i) {
    const double v = a[i] + t * coordDiff(space.circular[i], b[i], a[i]);
    r[i] = space.circular[i] ? wrapAngle(v) : v;
  }
  return r;
}

namespace {

void greedyPass(std::vector<Waypoint>& path, const SegmentFn& free) {
  if (path.size() < 3) return;
  std::vector<Waypoint> out{path.front()};
  std::size_t i = 0;
  while (i + 1 < path.size()) {
    // The farthest waypoint reachable directly from path[i]; path[i+1] always is.
    std::size_t j = path.size() - 1;
    while (j > i + 1 && !free(path[i], path[j])) --j;
    out.push_back(path[j]);
    i = j;
  }
  path = std::move(out);
}

// A point at parameter s along segment index `seg` (s in [0, 1]).
Waypoint pointOn(const JointSpace& space, const std::vector<Waypoint>& path, std::size_t seg, double s) {
  return interpolate(space, path[seg], path[seg + 1], s);
}

}  // namespace

void shortcutPath(const JointSpace& space, std::vector<Waypoint>& path, const SegmentFn& free, int attempts, Rng& rng) {
  greedyPass(path, free);
  for (int a = 0; a < attempts && path.size() >= 2; ++a) {
    const std::size_t segments = path.size() - 1;
    std::size_t s1 = rng.index(segments), s2 = rng.index(segments);
    double t1 = rng.uniform(), t2 = rng.uniform();
    if (s1 > s2 || (s1 == s2 && t1 > t2)) {
      std::swap(s1, s2);
      std::swap(t1, t2);
    }
    if (s1 == s2) continue;  // a shortcut within one straight segment gains nothing
    const Waypoint p1 = pointOn(space, path, s1, t1), p2 = pointOn(space, path, s2, t2);
    double before = l1Distance(space, p1, path[s1 + 1]) + l1Distance(space, path[s2], p2);
    for (std::size_t k = s1 + 1; k < s2; ++k) before += l1Distance(space, path[k], path[k + 1]);
    if (l1Distance(space, p1, p2) >= before - 1e-9) continue;
    if (!free(p1, p2)) continue;
    std::vector<Waypoint> out(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(s1) + 1);
    out.push_back(p1);
    out.push_back(p2);
    out.insert(out.end(), path.begin() + static_cast<std::ptrdiff_t>(s2) + 1, path.end());
    path = std::move(out);
  }
  greedyPass(path, free);
}

}  // namespace cbtl::world
