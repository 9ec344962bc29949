// The only translation unit that includes OMPL (slow to compile).
#include "robot/world/MotionPlanner.h"

#include "robot/world/SegmentCertificate.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace cbtl::world {

const char* toString(PlanStatus s) {
  switch (s) {
    case PlanStatus::Solved:
      return "solved";
    case PlanStatus::InvalidStart:
      return "invalid start";
    case PlanStatus::InvalidGoal:
      return "invalid goal";
    case PlanStatus::BudgetExhausted:
      return "iteration budget exhausted";
    case PlanStatus::NoMobileBase:
      return "scene has no mobile base";
  }
  return "unknown";
}

namespace {

// OMPL's process-wide set-up: a fixed global seed before any OMPL random generator exists (nothing on our
// path draws from OMPL's generators, see MotionPlanner.h; the seed is a safeguard), and warnings-only logging.
void initialiseOmpl() {
  static std::once_flag once;
  std::call_once(once, [] {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(1);
  });
}

struct Dim {
  bool circular;
  double lo, hi;
};

// A compound space of one SO(2) or bounded R¹ component per coordinate.
std::shared_ptr<ob::CompoundStateSpace> makeSpace(const std::vector<Dim>& dims) {
  auto space = std::make_shared<ob::CompoundStateSpace>();
  for (const Dim& d : dims) {
    if (d.circular) {
      space->addSubspace(std::make_shared<ob::SO2StateSpace>(), 1.0);
    } else {
      auto r = std::make_shared<ob::RealVectorStateSpace>(1);
      r->setBounds(d.lo, d.hi);
      space->addSubspace(r, 1.0);
    }
  }
  return space;
}

Waypoint toWaypoint(const std::vector<Dim>& dims, const ob::State* s) {
  const auto* c = s->as<ob::CompoundState>();
  Waypoint w(dims.size());
  for (std::size_t i = 0; i < dims.size(); ++i)
    w[i] = dims[i].circular ? c->as<ob::SO2StateSpace::StateType>(static_cast<unsigned>(i))->value
                            : c->as<ob::RealVectorStateSpace::StateType>(static_cast<unsigned>(i))->values[0];
  return w;
}

void fromWaypoint(const std::vector<Dim>& dims, const Waypoint& w, ob::State* s) {
  auto* c = s->as<ob::CompoundState>();
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (dims[i].circular)
      c->as<ob::SO2StateSpace::StateType>(static_cast<unsigned>(i))->value = wrapAngle(w[i]);
    else
      c->as<ob::RealVectorStateSpace::StateType>(static_cast<unsigned>(i))->values[0] = w[i];
  }
}

// Uniform and near samplers over the caller's random engine (OMPL's own samplers use its global RNG).
class SeededSampler : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::vector<Dim> dims, std::uint64_t seed)
      : ob::StateSampler(space), dims_(std::move(dims)), rng_(seed) {}

  void sampleUniform(ob::State* state) override {
    Waypoint w(dims_.size());
    for (std::size_t i = 0; i < dims_.size(); ++i) w[i] = uniform(dims_[i].lo, dims_[i].hi);
    fromWaypoint(dims_, w, state);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    Waypoint w = toWaypoint(dims_, near);
    for (std::size_t i = 0; i < dims_.size(); ++i) w[i] = clampDim(i, w[i] + uniform(-distance, distance));
    fromWaypoint(dims_, w, state);
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stdDev) override {
    Waypoint w = toWaypoint(dims_, mean);
    for (std::size_t i = 0; i < dims_.size(); ++i) w[i] = clampDim(i, w[i] + rng_.normal(0.0, stdDev));
    fromWaypoint(dims_, w, state);
  }

 private:
  double uniform(double lo, double hi) { return rng_.uniform(lo, hi); }
  double clampDim(std::size_t i, double v) const {
    return dims_[i].circular ? wrapAngle(v) : std::clamp(v, dims_[i].lo, dims_[i].hi);
  }
  std::vector<Dim> dims_;
  Rng rng_;
};

// Edges are accepted only when certified whole (SegmentCertificate.h through the planner's SegmentFn).
class CertifiedMotionValidator : public ob::MotionValidator {
 public:
  CertifiedMotionValidator(const ob::SpaceInformationPtr& si, std::vector<Dim> dims, SegmentFn free)
      : ob::MotionValidator(si), dims_(std::move(dims)), free_(std::move(free)) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool ok = free_(toWaypoint(dims_, s1), toWaypoint(dims_, s2));
    (ok ? valid_ : invalid_)++;
    return ok;
  }

  // Planners that want the last valid state of a blocked edge get its start: certification proves a whole
  // segment, not where a blocked one stops being free (RRTConnect never asks).
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& lastValid) const override {
    if (checkMotion(s1, s2)) return true;
    if (lastValid.first) si_->copyState(lastValid.first, s1);
    lastValid.second = 0.0;
    return false;
  }

 private:
  std::vector<Dim> dims_;
  SegmentFn free_;
};

struct GenericResult {
  PlanStatus status = PlanStatus::BudgetExhausted;
  std::vector<Waypoint> path;
  int iterations = 0;
};

GenericResult planGeneric(const std::vector<Dim>& dims, const ValidityFn& valid, const SegmentFn& free,
                          const Waypoint& start, const Waypoint& goal, Rng& rng, const PlanOptions& o) {
  initialiseOmpl();
  GenericResult result;
  JointSpace js;
  for (const Dim& d : dims) js.circular.push_back(d.circular);
  if (!valid(start)) {
    result.status = PlanStatus::InvalidStart;
    return result;
  }
  if (!valid(goal)) {
    result.status = PlanStatus::InvalidGoal;
    return result;
  }
  // Try the straight segment first: in open space it is the whole answer.
  if (o.tryDirectFirst && free(start, goal)) {
    result.status = PlanStatus::Solved;
    result.path = {start, goal};
    return result;
  }

  auto space = makeSpace(dims);
  const std::uint64_t samplerSeed = rng.next();
  space->setStateSamplerAllocator([dims, samplerSeed](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<SeededSampler>(s, dims, samplerSeed);
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&dims, &valid](const ob::State* s) { return valid(toWaypoint(dims, s)); });
  si->setMotionValidator(std::make_shared<CertifiedMotionValidator>(si, dims, free));
  si->setup();

  ob::ScopedState<> s(space), g(space);
  fromWaypoint(dims, start, s.get());
  fromWaypoint(dims, goal, g.get());
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(s, g);
  auto planner = std::make_shared<og::RRTConnect>(si);
  planner->setProblemDefinition(pdef);
  if (o.range > 0) planner->setRange(o.range);
  planner->setNearestNeighbors<ompl::NearestNeighborsLinear>();  // deterministic (GNAT draws from OMPL's RNG)

  int iterations = 0;
  const int budget = o.maxIterations;
  const ob::PlannerTerminationCondition ptc([&iterations, budget] { return ++iterations > budget; });
  const ob::PlannerStatus st = planner->solve(ptc);
  result.iterations = std::min(iterations, budget);
  if (st != ob::PlannerStatus::EXACT_SOLUTION || !pdef->hasExactSolution()) return result;

  const auto& path = *pdef->getSolutionPath()->as<og::PathGeometric>();
  for (std::size_t i = 0; i < path.getStateCount(); ++i) result.path.push_back(toWaypoint(dims, path.getState(i)));
  // OMPL's wrapped SO(2) values can differ from the caller's by 2π; keep the caller's exact endpoints.
  result.path.front() = start;
  result.path.back() = goal;
  shortcutPath(js, result.path, free, o.shortcutAttempts, rng);
  result.status = PlanStatus::Solved;
  return result;
}

std::vector<Dim> armDims(const Scene& s) {
  std::vector<Dim> dims;
  for (int i = 0; i < kArmDof; ++i) dims.push_back({s.armContinuous(i), s.armLower(i), s.armUpper(i)});
  return dims;
}

Waypoint toWp(const ArmConfig& q) { return Waypoint(q.begin(), q.end()); }
ArmConfig toArm(const Waypoint& w) {
  ArmConfig q{};
  std::copy_n(w.begin(), kArmDof, q.begin());
  return q;
}

}  // namespace

JointSpace armSpace(const Scene& scene) {
  JointSpace js;
  for (int i = 0; i < kArmDof; ++i) js.circular.push_back(scene.armContinuous(i));
  return js;
}

bool armSegmentFree(Workspace& ws, const ArmConfig& a, const ArmConfig& b, const CollisionOptions& options,
                    long* states) {
  const Scene& s = ws.scene();
  if (!s.withinLimits(a) || !s.withinLimits(b)) return false;
  const SegmentReport r = certifyArmSegment(ws, a, b, options);
  if (states) *states += r.states;
  return r.free();
}

ArmPlan planArm(Workspace& ws, const ArmConfig& start, const ArmConfig& goal, Rng& rng, const PlanOptions& o) {
  const Scene& s = ws.scene();
  long checks = 0;
  const ValidityFn valid = [&](const Waypoint& w) {
    const ArmConfig q = toArm(w);
    ++checks;
    return s.withinLimits(q) && checkArm(ws, q, o.collision).free();
  };
  const SegmentFn free = [&](const Waypoint& a, const Waypoint& b) {
    return armSegmentFree(ws, toArm(a), toArm(b), o.collision, &checks);
  };
  GenericResult r = planGeneric(armDims(s), valid, free, toWp(start), toWp(goal), rng, o);
  ws.setArm(start);
  ArmPlan plan;
  plan.status = r.status;
  plan.iterations = r.iterations;
  plan.validityChecks = checks;
  const JointSpace js = armSpace(s);
  for (std::size_t i = 0; i < r.path.size(); ++i) {
    plan.path.push_back(toArm(r.path[i]));
    if (i > 0) plan.length += l1Distance(js, r.path[i - 1], r.path[i]);
  }
  return plan;
}

BasePlan planBase(Workspace& ws, const Pose2& goal, Rng& rng, const PlanOptions& o) {
  BasePlan plan;
  if (!ws.scene().hasMobileBase()) {
    plan.status = PlanStatus::NoMobileBase;
    return plan;
  }
  const Pose2 start = ws.state().base;
  double b[4] = {o.baseBounds[0], o.baseBounds[1], o.baseBounds[2], o.baseBounds[3]};
  if (b[0] >= b[1] || b[2] >= b[3]) {
    b[0] = std::min(start.x, goal.x) - 0.5;
    b[1] = std::max(start.x, goal.x) + 0.5;
    b[2] = std::min(start.y, goal.y) - 0.5;
    b[3] = std::max(start.y, goal.y) + 0.5;
  }
  const std::vector<Dim> dims{{false, b[0], b[1]}, {false, b[2], b[3]}, {true, -std::numbers::pi, std::numbers::pi}};
  auto inBounds = [&](const Waypoint& w) { return w[0] >= b[0] && w[0] <= b[1] && w[1] >= b[2] && w[1] <= b[3]; };
  long checks = 0;
  const ValidityFn valid = [&](const Waypoint& w) {
    ++checks;
    if (!inBounds(w)) return false;
    ws.setBase({w[0], w[1], w[2]});
    return checkRobotCollisions(ws, o.collision).free();
  };
  // The bounds are a box, so a segment between two in-bounds ends stays in bounds.
  const SegmentFn free = [&](const Waypoint& a, const Waypoint& e) {
    if (!inBounds(a) || !inBounds(e)) return false;
    const SegmentReport r = certifyBaseSegment(ws, {a[0], a[1], a[2]}, {e[0], e[1], e[2]}, o.collision);
    checks += r.states;
    return r.free();
  };
  GenericResult r = planGeneric(dims, valid, free, {start.x, start.y, start.yaw}, {goal.x, goal.y, goal.yaw}, rng, o);
  ws.setBase(start);
  plan.status = r.status;
  plan.iterations = r.iterations;
  plan.validityChecks = checks;
  for (const auto& w : r.path) plan.path.push_back({w[0], w[1], w[2]});
  return plan;
}

}  // namespace cbtl::world
