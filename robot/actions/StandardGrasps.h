// StandardGrasps.h — the fixed grasps of the home scene's objects.
//
// Duster: the gripper pinches the pole from above at the scene's site `duster_grasp` (0.32 m from the head
// centre along the pole). Tool z points along the duster's -z (down when the duster lies flat) leaned by
// kDusterGraspTilt about the duster's y towards its -x; the fingers close across the pole (in the duster's
// x-z plane); the pole's axis lies kDusterGraspHeight ahead of the tool frame along tool z, inside the finger
// span and high enough that the finger tips clear the table the duster lies on. The lean lets the arm reach
// the duster on the main table (x = -0.75) from the table's approach base (0, -0.1, 0): a vertical tool
// there is just out of reach of the Gen3 (checked with IK). The duster has kDusterGraspCount standard grasps:
// grasp 0 is the one above (the scene's duster_tool site); the others pinch the pole at other points or with the
// fingers turned, so that an object lying beside one grasp point leaves another free (a plan chooses one: Cleaning's
// fetchDuster moves the arm to it before grasp()). `grasp("duster")` grasps at whichever standard grasp the tool
// is at, and otherwise drives the arm to grasp 0 by itself. A pre-wipe pose uses the grasp the duster is held at.
//
// Book (carry grasp, used for a book the robot holds when an episode starts): the fingers close across the
// book's thin x axis, tool z along the book's +y (its depth), book centre kBookGraspDepth ahead of the tool
// frame. Books are otherwise grasped where the plan put the gripper (fetchBook moves the arm first).
// Frames: an "X in Y" pose is X's frame expressed in Y's frame; units metres and radians.
#pragma once

#include "robot/world/WorldOperations.h"

#include <optional>
#include <string_view>

namespace cbtl::actions {

inline constexpr double kDusterGraspHeight = 0.045;  // pole axis ahead of the tool frame along tool z, metres
inline constexpr double kDusterGraspTilt = 0.1;      // radians the tool leans from vertical
inline constexpr double kDusterGraspTwist = 0.4;     // radians grasps 5-9 turn the fingers about the tool's z
inline constexpr double kBookGraspDepth = 0.03;      // book centre ahead of the tool frame, metres
inline constexpr int kDusterGraspPoints = 5;         // points of the pole the duster's standard grasps pinch
inline constexpr int kDusterGraspCount = 2 * kDusterGraspPoints;

// The tool frame in the duster's body frame at standard grasp `k` (0 <= k < kDusterGraspCount): the pole point
// 0.32, 0.26, 0.20, 0.16 or 0.36 m from the head centre (k mod 5; grasp 0 at the scene's duster_grasp site,
// (0, -0.32, -0.03) in home.xml), the tool leaned kDusterGraspTilt about the pole, and for k >= 5 the fingers
// turned kDusterGraspTwist about the tool's z (still closing across the pole).
world::Pose3 dusterToolInBody(int k = 0);
// The tool frame in a book's body frame at the carry grasp.
world::Pose3 bookToolInBody();

// How many standard grasps `object` has: kDusterGraspCount for the duster, 0 for any other object (which has no
// approach of its own).
int standardGraspCount(std::string_view object);
// The tool frame in `object`'s body frame at its standard grasp `k`; nullopt when it has no such grasp.
std::optional<world::Pose3> standardGraspInBody(std::string_view object, int k);
// The world tool pose of `object`'s standard grasp `k` at its current pose; nullopt when it has no such grasp.
std::optional<world::Pose3> standardGraspTool(const world::World& w, std::string_view object, int k = 0);

}  // namespace cbtl::actions
