// TableSlide.h — Feeding's movePlate(xy) and moveDrink(xy) (declared in feeding.cbtl): the caregiver slides
// the plate or the drink over the table to (x, y), keeping its height and orientation.
//
// World frame, metres. The executor contract is RobotActions.h's: an ill-formed call (not one vec<2>) is
// wellFormed == false and takes no step; otherwise one step, and a failure leaves the world unchanged:
// InvalidArgument (a coordinate is not finite, the body is unknown or held by the robot) or Blocked (the
// body at (x, y) would touch the scenery or another object, or would not stand on the table: Support.h).
#pragma once

#include "robot/actions/RobotActions.h"

#include <string>

namespace cbtl::domains::feeding {

// True for "movePlate" and "moveDrink".
bool isTableSlide(const std::string& action);

// Runs movePlate / moveDrink (`call.name`, one of isTableSlide's) on `w`.
actions::RobotActionResult slideOnTable(world::World& w, const sim::ActionCall& call);

}  // namespace cbtl::domains::feeding
