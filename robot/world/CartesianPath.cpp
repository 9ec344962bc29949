#include "robot/world/CartesianPath.h"

#include "robot/world/JointPath.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/MotionQuery.h"

#include <algorithm>
#include <cmath>

namespace cbtl::world {

namespace {

// What shapes the line besides the world state, the target and the collision options: the line's step limits and
// the options of its IK steps (those cartesianToolPath does not override).
std::vector<double> lineOptions(const IkOptions& ik, const CartesianPathOptions& o) {
  std::vector<double> v{o.maxStep,
                        o.maxAngle,
                        o.maxJointStep,
                        static_cast<double>(o.maxSteps),
                        o.checkCollisions ? 1.0 : 0.0,
                        static_cast<double>(ik.maxIterations),
                        ik.damping,
                        ik.maxStep,
                        ik.positionTolerance,
                        ik.rotationTolerance,
                        ik.nullspaceGain,
                        static_cast<double>(ik.site)};
  v.insert(v.end(), ik.rest.begin(), ik.rest.end());
  return v;
}

std::optional<std::vector<ArmConfig>> followLine(Workspace& ws, const Pose3& target, const IkOptions& ik,
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

}  // namespace

std::optional<std::vector<ArmConfig>> cartesianToolPath(Workspace& ws, const Pose3& target, const IkOptions& ik,
                                                        const CartesianPathOptions& options) {
  MotionCache& cache = ws.scene().motionCache();
  const MotionQuery q = lineQuery(ws, target, options.collision, lineOptions(ik, options));
  if (auto hit = cache.find(q, 0)) {
    if (!hit->solved()) return std::nullopt;
    return hit->arm;
  }
  auto path = followLine(ws, target, ik, options);
  MotionAnswer answer;
  answer.status = path ? PlanStatus::Solved : PlanStatus::InvalidGoal;  // no budget: the line is what it is
  if (path) answer.arm = *path;
  cache.store(q, std::move(answer));
  return path;
}

}  // namespace cbtl::world
