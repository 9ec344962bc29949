#include "robot/world/MotionQuery.h"

#include "runtime/core/Rng.h"

#include <cstring>

namespace cbtl::world {

namespace {

void appendPose(std::vector<double>& k, const Pose3& p) {
  k.insert(k.end(), {p.position.x(), p.position.y(), p.position.z(), p.orientation.w(), p.orientation.x(),
                     p.orientation.y(), p.orientation.z()});
}

// The world state and options every query shares: base, arm, gripper, the held object and its grasp, the
// movable objects in the scene's order, then the options that shape a plan.
std::vector<double> stateKey(const Workspace& ws, MotionKind kind, const PlanOptions& o) {
  const WorldState& s = ws.state();
  std::vector<double> k;
  k.reserve(40 + 7 * ws.scene().objects().size());
  k.push_back(static_cast<double>(kind));
  k.insert(k.end(), {s.base.x, s.base.y, s.base.yaw});
  k.insert(k.end(), s.arm.begin(), s.arm.end());
  k.push_back(s.gripper);
  k.push_back(static_cast<double>(ws.heldObject()));
  if (s.held) appendPose(k, s.held->toolToObject);
  for (const ObjectInfo& obj : ws.scene().objects()) {
    const auto it = s.objects.find(obj.name);
    if (it != s.objects.end()) appendPose(k, it->second);
  }
  for (const auto& [name, pose] : s.fixtures) appendPose(k, pose);
  k.insert(k.end(), {static_cast<double>(o.shortcutAttempts), o.range, o.tryDirectFirst ? 1.0 : 0.0});
  k.push_back(static_cast<double>(o.collision.allowances.size()));
  for (const ContactAllowance& a : o.collision.allowances)
    k.insert(k.end(),
             {static_cast<double>(a.part), static_cast<double>(a.geom), static_cast<double>(a.body), a.separation});
  k.insert(k.end(), std::begin(o.baseBounds), std::end(o.baseBounds));
  return k;
}

}  // namespace

std::uint64_t fingerprintOf(const std::vector<double>& values) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : values) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xffu;
      h *= 0x100000001b3ULL;
    }
  }
  return rt::splitMix64(h);
}

MotionQuery armQuery(const Workspace& ws, const ArmConfig& goal, const PlanOptions& options) {
  MotionQuery q;
  q.kind = MotionKind::Arm;
  q.key = stateKey(ws, q.kind, options);
  q.key.insert(q.key.end(), goal.begin(), goal.end());
  q.fingerprint = fingerprintOf(q.key);
  return q;
}

MotionQuery baseQuery(const Workspace& ws, const Pose2& goal, const PlanOptions& options) {
  MotionQuery q;
  q.kind = MotionKind::Base;
  q.key = stateKey(ws, q.kind, options);
  q.key.insert(q.key.end(), {goal.x, goal.y, goal.yaw});
  q.fingerprint = fingerprintOf(q.key);
  return q;
}

MotionQuery lineQuery(const Workspace& ws, const Pose3& target, const CollisionOptions& collision,
                      const std::vector<double>& lineOptions) {
  MotionQuery q;
  q.kind = MotionKind::Line;
  PlanOptions o;
  o.collision = collision;
  q.key = stateKey(ws, q.kind, o);
  appendPose(q.key, target);
  q.key.insert(q.key.end(), lineOptions.begin(), lineOptions.end());
  q.fingerprint = fingerprintOf(q.key);
  return q;
}

std::optional<MotionAnswer> MotionCache::find(const MotionQuery& q, int budget) {
  std::lock_guard lock(mutex_);
  const auto it = entries_.find(q.fingerprint);
  if (it == entries_.end() || it->second.kind != q.kind || it->second.key != q.key ||
      !it->second.answer.answers(budget)) {
    ++stats_.misses;
    return std::nullopt;
  }
  ++stats_.hits;
  return it->second.answer;
}

void MotionCache::store(const MotionQuery& q, MotionAnswer answer) {
  std::lock_guard lock(mutex_);
  if (capacity_ == 0) return;
  ++stats_.stored;
  const bool inserted = entries_.insert_or_assign(q.fingerprint, Entry{q.kind, q.key, std::move(answer)}).second;
  if (!inserted) return;  // a re-plan with a larger budget (or a collision) replaced the entry in place
  order_.push_back(q.fingerprint);
  while (entries_.size() > capacity_ && !order_.empty()) {
    entries_.erase(order_.front());
    order_.pop_front();
    ++stats_.evicted;
  }
}

ArmPlan planArmCached(Workspace& ws, const ArmConfig& goal, const PlanOptions& options) {
  const MotionQuery q = armQuery(ws, goal, options);
  MotionCache& cache = ws.scene().motionCache();
  ArmPlan plan;
  if (auto hit = cache.find(q, options.maxIterations)) {
    plan.status = hit->status;
    plan.iterations = hit->iterations;
    plan.path = std::move(hit->arm);
    return plan;
  }
  Rng rng(q.fingerprint);
  plan = planArm(ws, ws.state().arm, goal, rng, options);
  MotionAnswer a;
  a.status = plan.status;
  a.budget = options.maxIterations;
  a.iterations = plan.iterations;
  a.arm = plan.path;
  cache.store(q, std::move(a));
  return plan;
}

BasePlan planBaseCached(Workspace& ws, const Pose2& goal, const PlanOptions& options) {
  const MotionQuery q = baseQuery(ws, goal, options);
  MotionCache& cache = ws.scene().motionCache();
  BasePlan plan;
  if (auto hit = cache.find(q, options.maxIterations)) {
    plan.status = hit->status;
    plan.iterations = hit->iterations;
    plan.path = std::move(hit->base);
    return plan;
  }
  Rng rng(q.fingerprint);
  plan = planBase(ws, goal, rng, options);
  MotionAnswer a;
  a.status = plan.status;
  a.budget = options.maxIterations;
  a.iterations = plan.iterations;
  a.base = plan.path;
  cache.store(q, std::move(a));
  return plan;
}

MotionCacheStats MotionCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void MotionCache::clear() {
  std::lock_guard lock(mutex_);
  entries_.clear();
  order_.clear();
}

}  // namespace cbtl::world
