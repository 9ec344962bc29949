// GraspClosure.h — where a parallel gripper's fingers stop when they close on an object, and whether they hold it.
//
// The scene's gripper has two fingers (bodies left_finger and right_finger, slide joints finger_left and
// finger_right, Scene::fingerTravel() metres each from open to closed). They close together, as a parallel gripper
// does; a finger stops where its geoms meet the object's. Each finger's first contact is found by conservative
// advancement along its slide axis with exact separations (GeomDistance.h): a finger that moves by s comes at most s
// nearer to anything, so stepping by the current separation never steps through the object.
//
// A grasp holds when both fingers touch the object within their travel; the gripper then closes to where both
// touch and squeezes by kGraspSqueeze, so each pad sinks into the object by about that much — within the declared
// compliance kGraspCompliance, which the checks allow between the gripper and what it holds and nothing more.
// An object nearer one finger than the other is pushed by the first to touch until the second touches (a parallel
// gripper centres what it grips); the push must stay within kGraspMaxPush and the object moves with it. A grasp
// whose fingers reach the end of their travel on one side or both without touching closes on air; one whose open
// gripper already overlaps the object (palm or fingers) is blocked. Both are failed grasps, never attachments.
// Frames: world; units: metres.
#pragma once

#include "robot/world/Workspace.h"

#include <string>

namespace cbtl::world {

inline constexpr double kGraspCompliance = 0.001;  // metres a finger pad (or the palm) may sink into a held object
inline constexpr double kGraspSqueeze = 0.0005;    // metres each pad presses in past first contact
inline constexpr double kGraspMaxPush = 0.005;     // metres the closing fingers may push an object off centre

enum class GraspStatus {
  Holds,        // both fingers touch the object; `gripper`, `push` and `width` describe the closed grasp
  ClosesOnAir,  // a finger reaches the end of its travel without touching the object (or the push is too long)
  Blocked,      // the open gripper already overlaps the object beyond the compliance
  NoGripper,    // the scene has no two-finger gripper
};

const char* toString(GraspStatus s);

struct GraspClosure {
  GraspStatus status = GraspStatus::NoGripper;
  double gripper = 1.0;  // WorldState::gripper at the closed grasp (1 open, 0 fully closed)
  double width = 0.0;    // metres between the finger pads at the closed grasp
  double push = 0.0;     // metres the object moves along the closing axis (signed, towards the right finger)
  Eigen::Vector3d pushWorld = Eigen::Vector3d::Zero();  // that displacement in the world frame
  std::string detail;  // why it does not hold ("the left finger closes 12.3 mm short of drink_holder")
  bool holds() const { return status == GraspStatus::Holds; }
};

// How the gripper of `ws` closes on movable object `object` (an index into scene().objects()) from the current
// arm and base, with the gripper open and `object` not held. The Workspace is left as it was.
GraspClosure closeOn(Workspace& ws, int object);

// Closes the gripper of `ws` on the object it holds, as closeOn does (the object pushed to the centre, the
// gripper stopped where both fingers touch), for a state built with the object already in hand (an episode that
// starts holding it): the state's gripper value is replaced. On failure the Workspace is left as it was.
GraspClosure gripHeld(Workspace& ws);

// The least separation between the gripper's geoms (end_effector_link and the fingers) and the geoms of `object`
// at the current state (negative: the deepest penetration), with the geoms that realise it.
struct GripperContact {
  double separation = 0;
  int gripperGeom = -1, objectGeom = -1;
};
GripperContact gripperContact(const Workspace& ws, int object);

}  // namespace cbtl::world
