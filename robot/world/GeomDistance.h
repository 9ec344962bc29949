// GeomDistance.h — exact distances between two geoms of a scene at a Workspace's current state: the last word
// on whether two geoms touch, for the collision checks (Collision.h) and the certified segments
// (SegmentCertificate.h). MuJoCo's narrow phase is never consulted (MuJoCo 2.2.2's box-box test misses most shallow
// overlaps and reports phantom contacts when given a margin).
//
// How: sphere-sphere, sphere-capsule and capsule-capsule pairs in closed form (segment distances); a plane (the
// solid half-space below it) against anything in closed form (the other's lowest point); every other pair of convex
// shapes (boxes, cylinders, ellipsoids) as the widest empty slab between the two across a set of directions: the
// nearest-point direction FCL 0.7's GJK (or EPA's contact normal) suggests, the line between the centres, each
// solid's axes and their cross products (the separating-axis candidates, complete for two boxes). The slab's width
// comes from exact support functions, so it never exceeds the true distance whatever FCL answered (FCL 0.7's GJK
// was seen to place two boxes that overlap 2.3 mm apart); when FCL's direction is right it is the distance.
// Shapes are built once from the MJCF geoms (`geom_type`, `geom_size`), so the MJCF stays the single source of
// geometry. Meshes and height fields are not supported (no scene uses them): supports() says so and the caller
// treats such a geom with its bounding sphere.
//
// A cylinder's axis segment gives the nearest direction only against spheres and capsules; for a cylinder against
// a box, a cylinder or an ellipsoid whose nearest point lies over an end disc, the slab across the cylinder's axis is
// taken (exact there: the disc's plane separates them), otherwise the candidates above decide as for boxes.
//
// Guarantee: separation() is never above the true signed distance (so never reports two touching solids apart,
// and never an overlap shallower than it is). It is exact for round pairs, planes, two boxes that overlap and a
// solid facing a cylinder's end disc, and for the other pairs whenever FCL's direction is right. Units: metres.
// Thread safety: immutable after construction; one instance serves every thread (each call uses its own solver).
#pragma once

#include <mujoco/mujoco.h>

#include <limits>
#include <memory>

namespace cbtl::world {

class GeomDistance {
 public:
  explicit GeomDistance(const mjModel* m);
  ~GeomDistance();
  GeomDistance(const GeomDistance&) = delete;
  GeomDistance& operator=(const GeomDistance&) = delete;

  // Whether geom g has a shape this class measures (every primitive but meshes and height fields).
  bool supports(int g) const;

  // The separation of geoms g1 and g2 at the poses in `d` (geom_xpos / geom_xmat): their distance when apart, or
  // minus their penetration depth when they overlap (never above the truth, see above). Work stops as soon as the
  // bound exceeds `enough` (the caller only needs to know that much); with `needDepth` false an overlap is not
  // measured further once it is known (any negative value then means "overlapping, at least this deep").
  // Both geoms must be supported.
  double separation(const mjData* d, int g1, int g2, double enough = std::numeric_limits<double>::infinity(),
                    bool needDepth = true) const;

  // A lower bound on the separation of geoms g1 and g2 at every pose of a pure translation of g1 by s·v (v in
  // metres, world frame; s in [0, 1]) from the poses in `d`, g2 fixed. For a fixed direction u the empty slab
  // between two solids narrows by exactly s·(u·v) when one of them translates by s·v, so the slab's width at s = 0
  // less max(0, u·v) holds over the whole translation; the answer is the best over the candidate directions (both
  // solids' axes and their cross products, which do not turn, and the line between the centres at each end).
  // Never above the true signed distance anywhere on the translation; it may be far below it (a pair whose nearest
  // direction turns as it passes). Both geoms must be supported.
  double translationSeparation(const mjData* d, int g1, int g2, const double v[3]) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Closed-form helpers, exposed for tests and for the cheap bounds of Separation.h.
// Distance between segments [p0, p1] and [q0, q1] (points as 3 doubles).
double segmentSegmentDistance(const double* p0, const double* p1, const double* q0, const double* q1);
// Signed distance from point x to the solid box centred at c with rotation r (row-major, columns = the box's axes
// in the world frame) and half-sizes h: negative inside (minus the distance to the nearest face).
double pointBoxDistance(const double* x, const double* c, const double* r, const double* h);

}  // namespace cbtl::world
