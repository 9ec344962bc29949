// RobotDistance.h — how close the robot comes to some bodies of the scene: the smallest distance between the robot
// (its links, its gripper and the object it holds, visual-only geoms included) and the geoms of the given bodies,
// at the Workspace's current state, and the smallest slack to the separation each pair must keep (Separation.h
// requiredSeparation: margins and clearances, lowered by the allowances of `options`, as the collision checks do). For
// safety reports (Feeding: the clearance to the user per bite), not for planning: planners and IK keep out through
// those margins (Collision.h).
//
// Measured exactly (GeomDistance.h, never above the true distance); pairs farther apart than the cap are not
// measured. Units: metres.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/Workspace.h"

#include <string>
#include <vector>

namespace cbtl::world {

struct RobotDistance {
  double distance = 0;  // smallest distance (negative: penetration depth), or the cap when nothing is nearer
  std::string robotGeom, bodyGeom;  // the nearest pair's geom names (empty when nothing is within the cap)
  double keepOut = 0;               // the separation the nearest pair must keep
  // Smallest (distance - keep-out) over the measured pairs, or the cap: negative means a keep-out was entered.
  double slack = 0;
  std::string slackRobotGeom, slackBodyGeom;  // the pair of `slack` (empty when nothing is within the cap)
};

RobotDistance robotDistanceTo(Workspace& ws, const std::vector<int>& bodies, double cap = 0.5,
                              const CollisionOptions& options = {});

}  // namespace cbtl::world
