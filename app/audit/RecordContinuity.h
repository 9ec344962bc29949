// RecordContinuity.h — whether a run's record of motions leaves nothing out, and which plans the audit rejects.
//
// The record (runtime/approach/RunDirectory.h) marks each accepted plan before its motions and each time the robot
// was put back without a motion (an evaluation episode's start, a caregiver's reset). Between two such resets of a
// phase ("train", "eval") every motion must start where the phase's previous motion left the robot (arm and base):
// otherwise the robot moved in a way the record does not show, and the audit could not have checked it.
//
// Plans: a plan that a dry run accepted and whose motions the audit finds fault with (a violation, or a gap in the
// record) is a dry-run mismatch found by a check that shares nothing with the executor that ran the dry run; the
// run's own count of dry-run mismatches (plans that failed when executed) cannot show one, as the dry run and the
// simulator execute with the same code.
//
// Records written before the marks existed carry none: continuity is then not checked (checked() is false).
// Units: radians (arm joints, yaw), metres (base position).
#pragma once

#include "robot/world/MotionRecord.h"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

namespace cbtl::app {

struct PlanTally {
  std::int64_t plans = 0;           // accepted plans the record marks
  std::int64_t dryRun = 0;          // of them, accepted by a dry run
  std::int64_t dryRunRejected = 0;  // of those, with a motion the audit rejects (or a gap before one)
  std::int64_t gaps = 0;            // motions that did not start where the robot was left
};

class RecordContinuity {
 public:
  explicit RecordContinuity(const world::Scene& scene) : scene_(scene) {}

  // The robot of `phase` was put back: its next motion may start anywhere.
  void reset(const std::string& phase);
  // A plan of `phase` begins; its motions follow.
  void plan(const std::string& phase, bool dryRun);
  // How far `motion` starts from where the phase's previous motion (since its last reset) left the robot: the largest
  // joint, yaw (rad) or base position (m) difference; 0 for the first motion after a reset. Counted as a gap above
  // kContinuityTolerance. `faulty`: the audit found a violation in this motion (the plan it belongs to is rejected).
  double motion(const std::string& phase, const world::ExecutedMotion& motion, bool faulty);

  bool checked() const { return marked_; }
  const PlanTally& tally() const { return tally_; }

 private:
  struct Phase {
    std::optional<std::pair<world::ArmConfig, world::Pose2>> left;  // where the last motion left arm and base
    bool dryRunPlan = false, rejected = false, inPlan = false;
  };
  const world::Scene& scene_;
  std::map<std::string, Phase> phases_;
  PlanTally tally_;
  bool marked_ = false;
};

// A recorded value is written with enough digits to read back the same double: any difference is a real one.
inline constexpr double kContinuityTolerance = 1e-9;

}  // namespace cbtl::app
