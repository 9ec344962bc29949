// ClearanceExceptions.h — a plan's declared exceptions to the scene's clearances (`allow` blocks of a skill,
// sim::ClearanceException on each call) turned into the contact allowances of the collision checks
// (world/Collision.h ContactAllowance), which the executor applies to every check of the call's action.
//
// A name is a scene body (the allowance covers it and every body below it in the scene tree) or, failing that, a
// scene geom. Units: metres.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/Scene.h"
#include "runtime/sim/DomainSimulator.h"

#include <string>
#include <vector>

namespace cbtl::actions {

// The allowances of `exceptions` in `scene`; false (with `error` naming the `allow` and the name) when a part is not
// robot, gripper or held, a name is neither a body nor a geom of the scene, or a separation is not finite.
bool resolveClearanceExceptions(const world::Scene& scene, const std::vector<sim::ClearanceException>& exceptions,
                                std::vector<world::ContactAllowance>& out, std::string& error);

}  // namespace cbtl::actions
