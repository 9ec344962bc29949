#include "robot/world/CartesianPath.h"

#include "robot/world/JointPath.h"
#include "robot/world/MotionPlanner.h"

#include <algorithm>
#include <cmath>

namespace cbtl::world {

std::optional<std::vector<ArmConfig>> cartesianToolPath(Workspace& ws, const Pose3& target, const IkOptions& ik,
                                                        const CartesianPathOptions& options) {
  const WorldState saved = ws.state();
  const Pose3 from = ws.toolPose();
  const double travel = (target.position - from.position).norm();
  const double turn = rotationDistance(from.orientation, target.orientation);
  const double wanted = std::ceil(std::max(travel / options.maxStep, turn / options.maxAngle));
  const int steps = std::isfinite(wanted) ? static_cast<int>(std::clamp(wanted, 1.0, double(options.maxSteps))) : 1;
  IkOptions stepIk = ik;
  stepIk.maxAttempts = 1;  // from the previous configuration only: a restart would leave the line's branch
  stepIk.requireCollisionFree = options.checkCollisions;
  stepIk.collision = options.collision;
  const JointSpace space = armSpace(ws.scene());
  std::vector<ArmConfig> path{saved.arm};
  Rng unused(0);  // one attempt draws nothing
  bool ok = true;
  for (int k = 1; k <= steps && ok; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Pose3 goal{from.position + t * (target.position - from.position),
                     from.orientation.slerp(t, target.orientation)};
    const ArmConfig previous = path.back();
    const IkResult r = solveIk(ws, goal, previous, unused, stepIk);
    ok = r.solved() &&
         linfDistance(space, Waypoint(previous.begin(), previous.end()), Waypoint(r.q.begin(), r.q.end())) <=
             options.maxJointStep &&
         (!options.checkCollisions || armSegmentFree(ws, previous, r.q, options.collision));
    if (ok) path.push_back(r.q);
  }
  ws.setState(saved);
  if (!ok) return std::nullopt;
  return path;
}

}  // namespace cbtl::world
