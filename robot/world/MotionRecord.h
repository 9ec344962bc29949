// MotionRecord.h — an executed motion as data: what the robot did, written to a run's record of executed motions
// (motions.jsonl) and read back by `cbtl audit`, which re-checks it without the code that planned it.
//
// One motion is one straight-line-by-piece path of the arm (the base and everything else fixed) or of the mobile
// base (the arm fixed), from the whole world state it started in, with the contacts the action declared for it
// (Collision.h ContactAllowance). Consecutive waypoints are joined by straight segments: joint-space for the arm
// (continuous joints the short way round), x, y and yaw (the short way) for the base.
//
// JSON (one object, one line): {"kind": "arm" | "base",
//   "start": {"arm": [7 rad], "base": [x, y, yaw], "gripper": g, "objects": {name: [x, y, z, qw, qx, qy, qz]},
//             "fixtures": {name: [...]}, "held": name, "grasp": [x, y, z, qw, qx, qy, qz]  (tool frame → object)},
//   "path": [[7 rad] ...] | [[x, y, yaw] ...],
//   "allow": [{"part": "held" | "gripper" | "robot", "geom": name, "body": name, "separation": metres}]}
// (ContactAllowance: a negative separation is an allowed contact depth; older records wrote "depth" instead.)
// Numbers are written with enough digits to read back the same doubles. Units: metres, radians; world frame.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/WorldState.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::world {

struct ExecutedMotion {
  enum class Kind : unsigned char { Arm, Base };
  Kind kind = Kind::Arm;
  WorldState start;                          // the world when the motion began (its arm or base = path front)
  std::vector<ArmConfig> arm;                // Kind::Arm: the waypoints, start first
  std::vector<Pose2> base;                   // Kind::Base: the waypoints, start first
  std::vector<ContactAllowance> allowances;  // the contacts the action declared for this motion
};

struct MotionRecordError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string motionToJson(const Scene& scene, const ExecutedMotion& motion);
// Throws MotionRecordError (what the record lacks or names that the scene does not have).
ExecutedMotion motionFromJson(const Scene& scene, const std::string& text);

}  // namespace cbtl::world
