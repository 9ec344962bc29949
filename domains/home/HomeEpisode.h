// HomeEpisode.h — building blocks of an episode's start in the home scene, shared by Cleaning and Books.
//
// Every episode starts from the same room: the base at the origin (yaw 0), the arm at the reference's
// initial configuration (initialArm(): home.xml's conf_homeSceneInitial), the gripper open, the duster on
// the main table where home.xml puts it, and every book parked outside the room (HomeScene.h parkedPose(k)
// for book_k); the domain then puts books on surfaces and may put an object in the robot's hand.
// The domains' random draws are world::Rng's (rt::Rng: index, uniform, permutation; runtime/core/Rng.h).
#pragma once

#include "robot/world/WorldOperations.h"

#include <cstddef>
#include <map>
#include <string>

namespace cbtl::domains::home {

inline constexpr std::size_t kBookCount = 9;  // book_0 .. book_8
std::string bookBody(std::size_t k);          // "book_k"

// The arm's configuration at the start of an episode: the home scene's named configuration homeSceneInitial
// (home.xml's conf_homeSceneInitial) of `scene`, the program's home scene. Throws std::runtime_error when the
// scene lacks it (not the home scene, or a broken installation).
world::ArmConfig initialArm(const world::Scene& scene);

// The room above in `scene`. `scenePoses` are the movable objects' poses as home.xml puts them (a fresh
// Workspace's state().objects).
world::WorldState emptyRoom(const world::Scene& scene, const std::map<std::string, world::Pose3>& scenePoses);

// Puts `object` in the robot's hand in `state`: arm at the configuration the domains carry it in while the
// base moves (the duster at configs::kHome, which holds its long pole clear of the robot; a book at
// configs::kRetract, folded over the base, which clears the bed and the user's arm), gripper closed, grasped
// with the duster's standard grasp or, for any other object, the book carry grasp (StandardGrasps.h).
void holdCarried(world::WorldState& state, const std::string& object);

// How many steps in a row a robot may stand idle (no plan found) before a caregiver steps in.
inline constexpr int kCaregiverPatience = 5;

// A caregiver puts a stuck robot back to an episode's start pose in `state`: base at the origin, the gripper's
// duster kept and carried (holdCarried), any other held object taken away (parked outside the room), the arm at
// the initial configuration when empty-handed.
void caregiverReset(world::WorldState& state, const world::Scene& scene);

}  // namespace cbtl::domains::home
