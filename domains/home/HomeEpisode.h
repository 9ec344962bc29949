// HomeEpisode.h — building blocks of an episode's start in the home scene, shared by Cleaning and Books.
//
// Every episode starts from the same room: the base at the origin (yaw 0), the arm at the reference's
// initial configuration (configs::kHomeSceneInitial), the gripper open, the duster on the main table where
// home.xml puts it, and every book parked outside the room (HomeScene.h parkedPose(k) for book_k); the
// domain then puts books on surfaces and may put an object in the robot's hand.
// The domains' random draws are world::Rng's (rt::Rng: index, uniform, permutation; runtime/core/Rng.h).
#pragma once

#include "robot/world/WorldOperations.h"

#include <cstddef>
#include <map>
#include <string>

namespace cbtl::domains::home {

inline constexpr std::size_t kBookCount = 9;  // book_0 .. book_8
std::string bookBody(std::size_t k);          // "book_k"

// The room above. `scenePoses` are the movable objects' poses as home.xml puts them (a fresh Workspace's
// state().objects).
world::WorldState emptyRoom(const std::map<std::string, world::Pose3>& scenePoses);

// Puts `object` in the robot's hand in `state`: arm at configs::kHome, gripper closed, grasped with the
// duster's standard grasp or, for any other object, the book carry grasp (StandardGrasps.h).
void holdAtHome(world::WorldState& state, const std::string& object);

}  // namespace cbtl::domains::home
