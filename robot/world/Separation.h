// Separation.h — the geom pairs the robot's checks measure, with the separation each must keep, and how far apart
// they are at the Workspace's current state: the common ground of the state checks (Collision.h) and the certified
// segments (SegmentCertificate.h).
//
// The pairs are the Scene's candidates (MuJoCo's filters, the <pair> elements), classified for the held object:
// robot × world (RobotWorld), robot × robot (SelfCollision), held object × world and held object × non-gripper
// robot links (HeldObject); held object × gripper pairs are dropped. Each pair's `required` separation is its
// keep-out (Scene::keepOut: margins and clearances), or the smaller separation of a ContactAllowance that covers it.
//
// Two measures per pair: lowerBound(), a few flops from the bounding spheres and, for boxes and planes, their true
// extent (valid whatever the shapes: never above the true distance), and exact(), GeomDistance's separation. A
// pair whose lower bound already exceeds what is needed is never measured exactly.
// Units: metres. Thread safety: pairsFor() caches one list per thread.
#pragma once

#include "robot/world/Collision.h"

#include <limits>
#include <vector>

namespace cbtl::world {

// Two solids nearer than this are in contact, whatever the required separation says (10 µm). Not a clearance: the
// resolution at which two exact checkers agree. The exact geometry here (separating axes, closed forms) and FCL's
// box-box and GJK tests, which `cbtl audit` uses, can disagree by about a micrometre at touching: a finger certified
// 0.9 µm from a book was in contact for FCL (issue 40's Books grid). Every pair whose required separation is at or
// above zero must keep at least this much; an allowed contact depth (a negative requirement) is left as declared.
inline constexpr double kContactDistance = 1e-5;

struct CheckedPair {
  int g1 = -1, g2 = -1;  // g1 moves with the robot (a robot geom or a geom of the held object)
  double required = 0;   // metres the pair must stay apart: kContactDistance or more, or negative (an allowed depth)
  CollisionStatus kind = CollisionStatus::RobotWorld;
};

// The pairs to check with `ws`'s held object and `options`' allowances, in the Scene's order (robot × world, then
// self, then the held object's). The reference stays valid until the calling thread's next call.
const std::vector<CheckedPair>& pairsFor(const Workspace& ws, const CollisionOptions& options);

// The separation the pair (g1, g2) must keep with `ws`'s held object and `options`' allowances: its keep-out
// (Scene::keepOut), or the smaller separation of an allowance that covers it; at or above zero, at least
// kContactDistance.
double requiredSeparation(const Workspace& ws, const CollisionOptions& options, int g1, int g2);

// A lower bound on the separation of geoms g1 and g2 at the current poses (never above the exact one).
double lowerBound(const mjModel* m, const mjData* d, int g1, int g2);
// The separation of the pair (GeomDistance::separation, with its `enough` and `needDepth`; the cheap lower bound for
// a shape GeomDistance does not support).
double exactSeparation(const Workspace& ws, int g1, int g2, double enough = std::numeric_limits<double>::infinity(),
                       bool needDepth = true);

// The first pair of `pairs` closer than its required separation at the current state, exactly measured; null when
// every pair keeps its separation. *slack (when given) receives that pair's separation minus its requirement.
const CheckedPair* firstViolation(const Workspace& ws, const std::vector<CheckedPair>& pairs, double* slack = nullptr);

}  // namespace cbtl::world
