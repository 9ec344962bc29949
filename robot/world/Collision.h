// Collision.h — collision checks of the robot (arm, gripper, mobile base, held object) against the world
// and itself at the Workspace's current state, with exact geometry (GeomDistance.h): contact is contact.
//
// Each checked pair must keep a separation: a geom's MJCF `margin`, or a <contact><pair> margin, is a keep-out
// distance (the feeding scene keeps the robot 2 cm from the user's head this way); without one the pair only must
// not touch (a separation of 0 — touching counts). A ContactAllowance, declared by the action that needs it, lets a
// part of the robot touch one body or geom up to a bounded depth instead (the held object resting on the surface
// it is placed on, the duster on the surface it wipes). Contacts between the held object and the gripper
// (end_effector_link and fingers) are not checked (the grasp is the gripper's business), nor are contacts that
// involve no robot body and no held object (an object resting on a table is not the robot's concern).
#pragma once

#include "robot/world/Workspace.h"

#include <string>
#include <vector>

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
  double depth =
      0.0;  // how far inside the pair's required separation, metres (positive; penetration when 0 is required)
  double required = 0.0;  // the separation that pair must keep (metres; negative: an allowed contact depth)
  std::string clearance;  // the scene clearance that set `required` ("" when none did; Scene::BodyClearance)
  bool free() const { return status == CollisionStatus::Free; }
  // "gripper_finger touches book_3_geom" / "... is 3.1 cm from user_forearm_r (clearance person at f:l:c needs 5 cm)"
  std::string describe() const;
};

// An exception to a pair's required separation (its keep-out, a clearance, or "contact is contact"), declared by a
// skill (`allow` in the .cbtl file) or by the action that needs it: `part` may come to `separation` metres of the
// geom `geom` (or of any geom of body `body`, when geom is -1); a negative separation lets it touch and sink in by
// that much. An allowance only ever lowers a requirement.
struct ContactAllowance {
  enum class Part : unsigned char { HeldObject, Gripper, Robot };  // Robot: any robot body, the gripper included
  Part part = Part::HeldObject;
  int geom = -1;
  int body = -1;
  double separation = 0.0;  // metres
  bool operator==(const ContactAllowance&) const = default;
};

const char* toString(ContactAllowance::Part part);  // "held", "gripper", "robot"

struct CollisionOptions {
  std::vector<ContactAllowance> allowances;
  bool operator==(const CollisionOptions&) const = default;
};

// Checks the current state of `ws`.
CollisionReport checkRobotCollisions(Workspace& ws, const CollisionOptions& options = {});
// Sets the arm to q (keeping base, objects and held object) and checks.
CollisionReport checkArm(Workspace& ws, const ArmConfig& q, const CollisionOptions& options = {});

}  // namespace cbtl::world
