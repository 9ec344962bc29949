// HomeScene.h — the scene a robot domain acts in, as the program names it, and where the home-scene domains
// (Cleaning, Books) keep objects that have left the room. No scene file is named here: the program's
// `world "..."` line names it (home.xml, feeding.xml), and a simulator receives it through ProgramFacts
// (domains/ProgramFacts.h), loaded once per process by the app.
//
// Frames and units: world frame of the scene (z up, metres, radians); the mobile base starts at the origin.
#pragma once

#include "domains/ProgramFacts.h"
#include "robot/world/Pose.h"
#include "robot/world/Scene.h"

#include <cstddef>
#include <memory>
#include <string_view>

namespace cbtl::domains::home {

// The scene of the program: `program.scene`, else `program.scenePath` loaded now. Throws std::invalid_argument
// naming `domain` when the program has neither (the simulator of a robot domain needs its scene),
// std::runtime_error with the loader's message when the file cannot be loaded.
std::shared_ptr<const world::Scene> programScene(const ProgramFacts& program, std::string_view domain);

// Where objects that have left the room are kept (a book the user took, a book not in this episode): a row
// of poses 20 m outside the walls, `slot` 0.5 m apart, upright. Far enough that no check of the room sees
// them; the state keeps them so that WorldState always lists every movable object.
world::Pose3 parkedPose(std::size_t slot);
// True when `pose` is one of the parked poses' region (x beyond 10 m).
bool isParked(const world::Pose3& pose);

}  // namespace cbtl::domains::home
