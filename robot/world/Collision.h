// Collision.h — collision checks of the robot (arm, gripper, mobile base, held object) against the world
// and itself, using MuJoCo's collision detection at the Workspace's current state.
//
// A contact counts when its penetration is deeper than `tolerance` (metres). A geom's MJCF `margin` is a keep-out
// distance: the robot (or what it holds) closer to it than the margin counts as penetrating by the difference (the
// feeding scene keeps the robot 2 cm from the user's head this way); geoms without a margin count only when they
// touch. Contacts between the held
// object and the gripper (end_effector_link and fingers) are ignored, as are contacts that involve no
// robot body and no held object (an object resting on a table is not the robot's concern).
#pragma once

#include "robot/world/Workspace.h"

#include <string>

namespace cbtl::world {

enum class CollisionStatus {
  Free,
  RobotWorld,     // an arm/base link touches scenery or a movable object
  SelfCollision,  // two robot links touch
  HeldObject,     // the held object touches scenery, another object or a non-gripper robot link
};

const char* toString(CollisionStatus s);

struct CollisionReport {
  CollisionStatus status = CollisionStatus::Free;
  std::string first, second;  // geom names of the first counted contact (empty when Free)
  double depth = 0.0;         // its penetration depth, metres (positive)
  bool free() const { return status == CollisionStatus::Free; }
};

enum class CollisionMethod {
  // Only the geom pairs that can involve the robot or the held object (precomputed by the Scene with
  // MuJoCo's filters), a bounding-sphere test, then MuJoCo's narrow-phase functions. Several times faster
  // than a full mj_collision because static-static and object-scenery pairs are never visited.
  RobotPairs,
  // MuJoCo's full mj_collision over the whole scene, contacts classified afterwards (the reference).
  FullScene,
};

struct CollisionOptions {
  double tolerance = 1e-4;  // penetration depth below which contacts are ignored
  CollisionMethod method = CollisionMethod::RobotPairs;
};

// Checks the current state of `ws`.
CollisionReport checkRobotCollisions(Workspace& ws, const CollisionOptions& options = {});
// Sets the arm to q (keeping base, objects and held object) and checks.
CollisionReport checkArm(Workspace& ws, const ArmConfig& q, const CollisionOptions& options = {});

}  // namespace cbtl::world
