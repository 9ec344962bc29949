#include "app/audit/RecordContinuity.h"

#include "robot/world/Scene.h"

#include <algorithm>
#include <cmath>

namespace cbtl::app {

void RecordContinuity::reset(const std::string& phase) {
  marked_ = true;
  phases_[phase].left.reset();
}

void RecordContinuity::plan(const std::string& phase, bool dryRun) {
  marked_ = true;
  Phase& p = phases_[phase];
  p.inPlan = true;
  p.dryRunPlan = dryRun;
  p.rejected = false;
  ++tally_.plans;
  if (dryRun) ++tally_.dryRun;
}

double RecordContinuity::motion(const std::string& phase, const world::ExecutedMotion& motion, bool faulty) {
  Phase& p = phases_[phase];
  double gap = 0;
  if (marked_ && p.left) {
    const auto& [arm, base] = *p.left;
    for (int i = 0; i < world::kArmDof; ++i) {
      const double d =
          scene_.armContinuous(i) ? world::angleDiff(motion.start.arm[i], arm[i]) : motion.start.arm[i] - arm[i];
      gap = std::max(gap, std::abs(d));
    }
    gap = std::max({gap, std::abs(motion.start.base.x - base.x), std::abs(motion.start.base.y - base.y),
                    std::abs(world::angleDiff(motion.start.base.yaw, base.yaw))});
  }
  if (gap > kContinuityTolerance) ++tally_.gaps;
  if ((faulty || gap > kContinuityTolerance) && p.inPlan && p.dryRunPlan && !p.rejected) {
    p.rejected = true;
    ++tally_.dryRunRejected;
  }
  // Only the robot is compared: objects may move without a robot motion (a caregiver's restock, a new meal).
  std::pair<world::ArmConfig, world::Pose2> left{motion.start.arm, motion.start.base};
  if (motion.kind == world::ExecutedMotion::Kind::Arm && !motion.arm.empty()) left.first = motion.arm.back();
  if (motion.kind == world::ExecutedMotion::Kind::Base && !motion.base.empty()) left.second = motion.base.back();
  p.left = left;
  return gap;
}

}  // namespace cbtl::app
