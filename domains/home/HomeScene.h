// HomeScene.h — the home scene of the Cleaning and Books domains (domains/home/home.xml), loaded once per
// process and shared read-only by every simulator and thread.
//
// Frames and units: world frame of the scene (z up, metres, radians); the mobile base starts at the origin.
#pragma once

#include "robot/world/Scene.h"

#include <cstddef>
#include <memory>
#include <string>

namespace cbtl::domains::home {

// The scene file compiled into the library (the source tree's domains/home/home.xml).
const std::string& homeScenePath();

// The loaded scene; the first call loads it (thread-safe). Throws std::runtime_error with the loader's
// message when the file is missing or does not compile: a broken installation, not a plan error.
std::shared_ptr<const world::Scene> homeScene();

// Where objects that have left the room are kept (a book the user took, a book not in this episode): a row
// of poses 20 m outside the walls, `slot` 0.5 m apart, upright. Far enough that no check of the room sees
// them; the state keeps them so that WorldState always lists every movable object.
world::Pose3 parkedPose(std::size_t slot);
// True when `pose` is one of the parked poses' region (x beyond 10 m).
bool isParked(const world::Pose3& pose);

}  // namespace cbtl::domains::home
