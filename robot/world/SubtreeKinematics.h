// SubtreeKinematics.h — forward kinematics of one body subtree of a MuJoCo model: the Workspace's fast path
// when only the arm, the base or a held object moved.
//
// Why: an IK step or a planner's state check changes the seven arm joints, yet mj_kinematics recomputes every
// body, geom and site of the scene, and a held object needed a second full pass after its pose was derived from
// the tool's. Profiling one Books trial put 56 % of its time inside mj_kinematics. A subtree pass recomputes only
// the bodies whose poses depend on the joints that changed (the arm's 11 bodies of the home scene's 29).
//
// Contract: update() assumes the parent of the subtree's root is current in mjData (xpos, xquat, xmat) and that
// qpos holds the new joint values. For every body of the subtree it fills what mj_kinematics fills: xpos, xquat,
// xmat, xipos, ximat; for their joints xanchor and xaxis; for their geoms and sites the world position and
// rotation matrix. Results equal mj_kinematics' to rounding (tests: SubtreeKinematics.*). Everything outside the
// subtree is left untouched. A subtree that contains a mocap body is not supported (supported() is false; the
// caller uses mj_kinematics).
// Frames: world coordinates; MuJoCo's conventions (quaternions w x y z, row-major 3x3 matrices).
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

namespace cbtl::world {

class KinematicSubtree {
 public:
  KinematicSubtree() = default;  // empty: update() does nothing, supported() is false
  // The subtree rooted at body `root` (root > 0).
  KinematicSubtree(const mjModel* m, int root);

  bool supported() const { return supported_; }
  int root() const { return bodies_.empty() ? -1 : bodies_.front(); }
  const std::vector<int>& bodies() const { return bodies_; }
  const std::vector<int>& geoms() const { return geoms_; }

  void update(const mjModel* m, mjData* d) const;

 private:
  std::vector<int> bodies_;  // in MuJoCo's order: every parent before its children
  std::vector<int> geoms_, sites_;
  bool supported_ = false;
};

}  // namespace cbtl::world
