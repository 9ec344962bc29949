// WorldState.h — the kinematic state of a robot scene, as plain data.
//
// Frames and units: object poses are body frames in world coordinates (metres, unit quaternions); the
// base pose is the mobile base in the world plane (ignored by scenes without a mobile base); arm joints in
// radians; gripper opening in [0, 1] (1 = fully open, 0 = closed).
// A held object follows the tool: its pose is tool_frame ∘ toolToObject, whatever `objects` says for it.
// Fixtures (Scene.h: scenery a scenario positions, such as the feeding scene's tables) are body frames in world
// coordinates too; no action moves them.
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
  ArmConfig arm{};                        // q1..q7
  Pose2 base;                             // mobile base pose
  double gripper = 1.0;                   // opening, 1 = open
  std::map<std::string, Pose3> objects;   // movable-object poses; objects not listed keep their current pose
  std::map<std::string, Pose3> fixtures;  // fixture poses; fixtures not listed keep their current pose
  std::optional<Grasp> held;
};

// Named arm configurations of the Gen3 (radians), from Kinova's published keyframes; every scene shares
// them. `retract` folds the arm over its base; `zero` points it straight up. Configurations of one scene
// (Feeding's abovePlate, the home scene's homeSceneInitial) live in that scene's file (NamedConfigurations.h).
namespace configs {
inline constexpr ArmConfig kZero{0, 0, 0, 0, 0, 0, 0};
inline constexpr ArmConfig kHome{0, 0.2618, 3.1416, -2.2689, 0, 0.9599, 1.5708};
inline constexpr ArmConfig kRetract{0, -0.3491, 3.1416, -2.5482, 0, -0.8727, 1.5708};
}  // namespace configs

}  // namespace cbtl::world
