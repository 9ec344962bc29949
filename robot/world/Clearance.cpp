// One of the two translation units that include FCL (slow to compile); GeomDistance.cpp is the other.
#include "robot/world/Clearance.h"

#include "robot/world/FclShapes.h"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>

namespace cbtl::world {

const char* toString(PlacementStatus s) {
  switch (s) {
    case PlacementStatus::Ok:
      return "ok";
    case PlacementStatus::UnknownObject:
      return "unknown object";
    case PlacementStatus::Collides:
      return "collides";
    case PlacementStatus::TooClose:
      return "too close to another object";
  }
  return "unknown";
}

struct ClearanceChecker::Impl {
  std::shared_ptr<const Scene> scene;
  // One shape per geom (null for geoms FCL does not handle or that are ignored), and the geom's pose in its
  // body frame.
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> shapes;
  std::vector<fcl::Transform3d> local;
  std::vector<LocalBox> boxes;  // per object

  fcl::Transform3d geomWorld(const Workspace& ws, int g) const { return geomWorldTransform(ws.data(), g); }

  static fcl::Transform3d toTransform(const Pose3& p) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() = p.orientation.normalized().toRotationMatrix();
    t.translation() = p.position;
    return t;
  }

  std::vector<int> geomsOfObject(int objectIndex) const {
    const mjModel* m = scene->model();
    std::vector<int> out;
    for (int g = 0; g < m->ngeom; ++g)
      if (shapes[static_cast<size_t>(g)] && scene->objectOfBody(m->geom_bodyid[g]) == objectIndex) out.push_back(g);
    return out;
  }
};

ClearanceChecker::ClearanceChecker(std::shared_ptr<const Scene> scene) : impl_(std::make_unique<Impl>()) {
  impl_->scene = std::move(scene);
  const mjModel* m = impl_->scene->model();
  impl_->shapes.resize(static_cast<size_t>(m->ngeom));
  impl_->local.resize(static_cast<size_t>(m->ngeom), fcl::Transform3d::Identity());
  for (int g = 0; g < m->ngeom; ++g) {
    const BodyKind kind = impl_->scene->bodyKind(m->geom_bodyid[g]);
    if (kind == BodyKind::Robot || kind == BodyKind::Gripper) continue;
    if (m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0) continue;
    std::shared_ptr<fcl::CollisionGeometryd> shape = fclShapeOf(m, g);
    if (!shape) continue;
    impl_->shapes[static_cast<size_t>(g)] = shape;
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.translation() = Eigen::Vector3d(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
    const mjtNum* q = m->geom_quat + 4 * g;
    t.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    impl_->local[static_cast<size_t>(g)] = t;
  }
  // Per-object bounding boxes in the body frame, from each shape's local AABB.
  for (size_t i = 0; i < impl_->scene->objects().size(); ++i) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
    for (int g : impl_->geomsOfObject(static_cast<int>(i))) {
      const auto& aabb = impl_->shapes[static_cast<size_t>(g)]->aabb_local;
      const fcl::Transform3d& t = impl_->local[static_cast<size_t>(g)];
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner((c & 1) ? aabb.max_.x() : aabb.min_.x(), (c & 2) ? aabb.max_.y() : aabb.min_.y(),
                                     (c & 4) ? aabb.max_.z() : aabb.min_.z());
        const Eigen::Vector3d w = t * corner;
        lo = lo.cwiseMin(w);
        hi = hi.cwiseMax(w);
      }
    }
    LocalBox box;
    if (lo.x() <= hi.x()) {
      box.center = 0.5 * (lo + hi);
      box.halfExtents = 0.5 * (hi - lo);
    }
    impl_->boxes.push_back(box);
  }
}

ClearanceChecker::~ClearanceChecker() = default;

std::optional<ClearanceChecker::LocalBox> ClearanceChecker::objectBox(std::string_view object) const {
  const int idx = impl_->scene->objectIndex(object);
  if (idx < 0) return std::nullopt;
  return impl_->boxes[static_cast<size_t>(idx)];
}

namespace {

double pairDistance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  fcl::DistanceRequestd req;
  req.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd res;
  fcl::distance(&a, &b, req, res);
  return std::max(0.0, res.min_distance);
}

// Whether two objects intersect (touching counts), and the deepest reported penetration.
bool intersects(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b, double* depth) {
  fcl::CollisionRequestd req(8, true);
  req.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd res;
  if (fcl::collide(&a, &b, req, res) == 0) return false;
  *depth = 0.0;
  for (std::size_t i = 0; i < res.numContacts(); ++i) *depth = std::max(*depth, res.getContact(i).penetration_depth);
  return true;
}

}  // namespace

double ClearanceChecker::objectDistance(std::string_view a, const Pose3& poseA, std::string_view b,
                                        const Pose3& poseB) const {
  const int ia = impl_->scene->objectIndex(a), ib = impl_->scene->objectIndex(b);
  if (ia < 0 || ib < 0) return -1.0;
  const auto ta = Impl::toTransform(poseA), tb = Impl::toTransform(poseB);
  double best = INFINITY;
  for (int ga : impl_->geomsOfObject(ia)) {
    const fcl::CollisionObjectd oa(impl_->shapes[static_cast<size_t>(ga)], ta * impl_->local[static_cast<size_t>(ga)]);
    for (int gb : impl_->geomsOfObject(ib)) {
      const fcl::CollisionObjectd ob(impl_->shapes[static_cast<size_t>(gb)],
                                     tb * impl_->local[static_cast<size_t>(gb)]);
      best = std::min(best, pairDistance(oa, ob));
    }
  }
  return std::isfinite(best) ? best : -1.0;
}

PlacementReport ClearanceChecker::checkPlacement(const Workspace& ws, std::string_view object, const Pose3& pose,
                                                 const PlacementOptions& options) const {
  const Scene& s = *impl_->scene;
  const mjModel* m = s.model();
  const int idx = s.objectIndex(object);
  if (idx < 0) return {PlacementStatus::UnknownObject, std::string(object), 0.0};
  const auto t = Impl::toTransform(pose);
  // Against the scenery the object is tested lifted by the tolerance, so that resting on a surface is fine.
  Pose3 lifted = pose;
  lifted.position.z() += options.contactTolerance;
  const auto tl = Impl::toTransform(lifted);
  std::vector<fcl::CollisionObjectd> mine, mineLifted;
  for (int g : impl_->geomsOfObject(idx)) {
    mine.emplace_back(impl_->shapes[static_cast<size_t>(g)], t * impl_->local[static_cast<size_t>(g)]);
    mineLifted.emplace_back(impl_->shapes[static_cast<size_t>(g)], tl * impl_->local[static_cast<size_t>(g)]);
  }

  // Scenery and other objects: no intersection.
  for (int g = 0; g < m->ngeom; ++g) {
    if (!impl_->shapes[static_cast<size_t>(g)]) continue;
    const int owner = s.objectOfBody(m->geom_bodyid[g]);
    if (owner == idx || (owner >= 0 && owner == ws.heldObject())) continue;
    const fcl::CollisionObjectd other(impl_->shapes[static_cast<size_t>(g)], impl_->geomWorld(ws, g));
    for (const auto& o : mineLifted) {
      double depth = 0.0;
      if (intersects(o, other, &depth)) return {PlacementStatus::Collides, s.geomName(g), depth};
    }
  }
  // Other movable objects: clearance.
  if (options.clearance > 0) {
    for (size_t j = 0; j < s.objects().size(); ++j) {
      const int jj = static_cast<int>(j);
      if (jj == idx || jj == ws.heldObject()) continue;
      double best = INFINITY;
      for (int g : impl_->geomsOfObject(jj)) {
        const fcl::CollisionObjectd other(impl_->shapes[static_cast<size_t>(g)], impl_->geomWorld(ws, g));
        for (const auto& o : mine) best = std::min(best, pairDistance(o, other));
      }
      if (best < options.clearance) return {PlacementStatus::TooClose, s.objects()[j].name, best};
    }
  }
  return {};
}

}  // namespace cbtl::world
