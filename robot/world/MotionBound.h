// MotionBound.h — how fast any point of the robot can move when its joints move: the Lipschitz constants the
// certified segments (SegmentCertificate.h) rest on.
//
// For every joint k of the robot (the arm's hinges, the mobile base's slides and yaw, the fingers' slides) and
// every body b that k moves, reach(k, b) bounds the distance from joint k's anchor to b's origin in *every*
// configuration: the triangle inequality along the kinematic chain from k's body down to b (each body adds its
// offset from its parent, `body_pos`, twice the offset of each of its hinge anchors, `jnt_pos`, and the largest
// travel of each of its slides). A point of b at most r from b's origin is then at most reach(k, b) + r from
// joint k's axis, so when joint k turns by Δ (rad) the point moves at most Δ·(reach + r); a slide moves it by its
// own travel. Summed over the joints that change, this bounds the displacement of every point of a geom over a
// straight joint-space segment, whatever the configuration along it (Schwarzer, Saha and Latombe's adaptive
// collision checking, T-RO 2005).
//
// Relative motion: a joint that moves both geoms of a pair turns them together and cannot change their distance
// (the distance between two points is invariant under a common rigid motion), so pairRate() counts only the
// joints that move exactly one of the two.
// Units: metres, radians. Immutable after construction; shared by every thread (the Scene owns one).
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

namespace cbtl::world {

class MotionBound {
 public:
  // `robotBody[b]` is true for the robot's bodies (arm, base, gripper, fingers): their hinge and slide joints are
  // the robot joints.
  MotionBound(const mjModel* m, const std::vector<bool>& robotBody);

  // The robot's joints as MuJoCo joint ids (hinge or slide), in id order; index k into this list names a joint.
  const std::vector<int>& joints() const { return joints_; }
  // k for MuJoCo joint id `joint`, or -1 when it is not a robot joint.
  int jointIndex(int joint) const;

  // Whether joint k moves body b (b lies in the subtree of the joint's body).
  bool moves(int k, int body) const { return reach_[index(k, body)] >= 0; }
  // Upper bound on the speed of any point of body b within r metres of b's origin per unit of joint k's
  // coordinate: reach(k, b) + r for a hinge (m/rad), 1 for a slide; 0 when joint k does not move b.
  double rate(int k, int body, double r) const;

 private:
  std::size_t index(int k, int body) const {
    return static_cast<std::size_t>(k) * nbody_ + static_cast<std::size_t>(body);
  }

  std::vector<int> joints_;
  std::vector<int> jointIndex_;  // per MuJoCo joint id
  std::vector<bool> slide_;      // per k
  std::vector<double> reach_;    // [k * nbody + b]: reach(k, b), or -1 when k does not move b
  std::size_t nbody_ = 0;
};

}  // namespace cbtl::world
