// WorldState.h — the kinematic state of a robot scene, as plain data.
//
// Frames and units: object poses are body frames in world coordinates (metres, unit quaternions); the
// base pose is the mobile base in the world plane (ignored by scenes without a mobile base); arm joints in
// radians; gripper opening in [0, 1] (1 = fully open, 0 = closed).
// A held object follows the tool: its pose is tool_frame ∘ toolToObject, whatever `objects` says for it.
#pragma once

#include "robot/world/Pose.h"

#include <map>
#include <optional>
#include <string>

namespace cbtl::world {

struct Grasp {
  std::string object;  // name of a movable object of the scene
  Pose3 toolToObject;  // the object's body frame in the tool_frame site's frame
};

struct WorldState {
  ArmConfig arm{};                       // q1..q7
  Pose2 base;                            // mobile base pose
  double gripper = 1.0;                  // opening, 1 = open
  std::map<std::string, Pose3> objects;  // movable-object poses; objects not listed keep their current pose
  std::optional<Grasp> held;
};

// Named arm configurations of the Gen3 (radians), from Kinova's published keyframes and the reference
// scenes. `retract` folds the arm over its base; `zero` points it straight up.
namespace configs {
inline constexpr ArmConfig kZero{0, 0, 0, 0, 0, 0, 0};
inline constexpr ArmConfig kHome{0, 0.2618, 3.1416, -2.2689, 0, 0.9599, 1.5708};
inline constexpr ArmConfig kRetract{0, -0.3491, 3.1416, -2.5482, 0, -0.8727, 1.5708};
inline constexpr ArmConfig kAbovePlate{-2.86495, -1.61461, -2.61159, -1.37673, 1.11843, -1.17905, -2.69574};
inline constexpr ArmConfig kUtensilAboveMount{-0.30812, 0.14493, -2.45151, -2.35393, -0.14376, -0.68726, 0.50281};
inline constexpr ArmConfig kDrinkGaze{-0.00419, 0.60346, -3.12590, -2.35380, 0.01149, 1.34116, 1.68252};
inline constexpr ArmConfig kHomeSceneInitial{1.0, -0.71, -3.14159265358979, -2.3, 0, 0, -1.5707963267949};
}  // namespace configs

}  // namespace cbtl::world
