// SegmentCertificate.h — proofs that a straight motion of the robot keeps every checked pair (Separation.h) at its
// required separation along the *whole* motion, not only at sampled points.
//
// The method (Schwarzer, Saha and Latombe's adaptive dynamic collision checking): over a straight segment in
// joint space, no point of a pair's moving geom moves, relative to the other geom, more than the pair's motion
// bound M (MotionBound.h: the sum over the joints that change of |Δq| times the joint's speed bound). A pair's
// separation is therefore M-Lipschitz in the segment's parameter, and if its slack (separation minus requirement)
// at the two ends adds up to more than M, it stays positive in between. A pair that fails the test is tested
// again on the two halves, with its slack measured exactly at the midpoint; a midpoint without slack is a
// violation. No resolution parameter is involved: the only approximations are conservative (bounding spheres for
// the cheap lower bounds, GJK results lowered by kIterativeSlack).
//
// Termination: a pair whose slack tends to zero somewhere along the segment without becoming negative (a graze)
// would need ever smaller halves; after kMaxDepth halvings (a piece 2^-kMaxDepth of the segment) the segment is
// declared Uncertain, which every caller treats as not free.
//
// The Workspace is left at an unspecified state of the segment. Units: metres, radians.
#pragma once

#include "robot/world/Collision.h"
#include "robot/world/Workspace.h"

namespace cbtl::world {

inline constexpr int kMaxCertificateDepth = 30;

enum class SegmentStatus {
  Certified,  // every checked pair keeps its separation along the whole segment
  Collides,   // a state on the segment (an end or a tested midpoint) violates a separation: `contact` says which
  Uncertain,  // no proof within kMaxCertificateDepth halvings (a graze): not free
};

const char* toString(SegmentStatus s);

struct SegmentReport {
  SegmentStatus status = SegmentStatus::Certified;
  CollisionReport contact;  // Collides / Uncertain: the pair (and, for Collides, how deep inside its separation)
  double at = 0;            // Collides / Uncertain: the segment parameter in [0, 1] where it was found
  long states = 0;          // states whose kinematics were computed
  long exactQueries = 0;    // exact pair measurements (GeomDistance)
  bool free() const { return status == SegmentStatus::Certified; }
};

// The arm moves from a to b (each joint linearly, continuous joints the short way round), everything else fixed.
// Joint limits are the caller's concern (a segment between two in-limit configurations stays in limits).
SegmentReport certifyArmSegment(Workspace& ws, const ArmConfig& a, const ArmConfig& b,
                                const CollisionOptions& options = {});
// The mobile base moves from a to b (x and y linearly, yaw the short way round), the arm fixed.
SegmentReport certifyBaseSegment(Workspace& ws, const Pose2& a, const Pose2& b, const CollisionOptions& options = {});

}  // namespace cbtl::world
