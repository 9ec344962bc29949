// StandardGrasps.h — the fixed grasps of the home scene's objects.
//
// Duster: the gripper pinches the pole from above at the scene's site `duster_grasp` (0.32 m from the head
// centre along the pole). Tool z points along the duster's -z (down when the duster lies flat) leaned by
// kDusterGraspTilt about the duster's y towards its -x; the fingers close across the pole (in the duster's
// x-z plane); the pole's axis lies kDusterGraspHeight ahead of the tool frame along tool z, inside the finger
// span and high enough that the finger tips clear the table the duster lies on. The lean lets the arm reach
// the duster on the main table (x = -0.75) from the table's approach base (0, -0.1, 0): a vertical tool
// there is just out of reach of the Gen3 (checked with IK). `grasp("duster")` drives the arm to this pose by
// itself (Cleaning's fetchDuster moves only the base), and a pre-wipe pose assumes this grasp.
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
inline constexpr double kBookGraspDepth = 0.03;      // book centre ahead of the tool frame, metres

// The tool frame in the duster's body frame at the standard grasp (uses the position of the scene's
// duster_grasp site in the body frame, (0, -0.32, -0.03) in home.xml).
world::Pose3 dusterToolInBody();
// The tool frame in a book's body frame at the carry grasp.
world::Pose3 bookToolInBody();

// The world tool pose of `object`'s standard grasp at its current pose: the duster only; nullopt for any
// other object (which has no approach of its own).
std::optional<world::Pose3> standardGraspTool(const world::World& w, std::string_view object);

}  // namespace cbtl::actions
