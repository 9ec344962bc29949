#include "robot/bind/WorldBuiltins.h"

#include "robot/actions/StandardGrasps.h"
#include "robot/bind/WorldHost.h"
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/Occlusion.h"
#include "robot/world/PreWipe.h"
#include "robot/world/Support.h"

#include <cmath>
#include <limits>

namespace cbtl::bind {

namespace {

using Args = std::span<const double>;
using Widths = std::span<const std::uint16_t>;
using Out = std::span<double>;
using world::ArmConfig;
using world::Pose2;
using world::Pose3;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint64_t kQuerySeed = 0x9e3779b97f4a7c15ULL;  // fixed seed of the searching functions

WorldHost& host(const rt::CallContext& cx) { return static_cast<WorldHost&>(*cx.host); }
std::string text(const rt::CallContext& cx, double id) {
  if (cx.strings == nullptr || !(id >= 0) || id >= static_cast<double>(cx.strings->size())) return {};
  return cx.strings->name(static_cast<std::uint32_t>(id));
}

Pose3 readPose(const double* a) {
  Pose3 p;
  p.position = Eigen::Vector3d(a[0], a[1], a[2]);
  Eigen::Quaterniond q(a[6], a[3], a[4], a[5]);
  p.orientation = q.norm() > 1e-12 ? q.normalized() : Eigen::Quaterniond::Identity();
  return p;
}
void writePose(const Pose3& p, double* o) {
  Eigen::Quaterniond q = p.orientation.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  o[0] = p.position.x();
  o[1] = p.position.y();
  o[2] = p.position.z();
  o[3] = q.x();
  o[4] = q.y();
  o[5] = q.z();
  o[6] = q.w();
}
void writeNaN(Out o) {
  for (double& x : o) x = kNaN;
}
ArmConfig readConf(const double* a) {
  ArmConfig q{};
  for (int i = 0; i < world::kArmDof; ++i) q[i] = a[i];
  return q;
}
Pose2 readSe2(const double* a) { return Pose2{a[0], a[1], a[2]}; }
const Pose2 kOrigin{};

bool finite(std::span<const double> v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

Pose3 toolDown(const Eigen::Vector3d& at, double yaw) {
  Pose3 p;
  p.position = at;
  p.orientation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
  return p;
}

std::optional<Pose3> referencePose(WorldHost& h, const std::string& object) {
  auto it = h.reference().objects.find(object);
  if (it != h.reference().objects.end()) return it->second;
  if (h.scene().objectIndex(object) < 0) return std::nullopt;
  h.pose(h.reference().base, h.reference().arm);
  return h.workspace().objectPose(object);
}

// ---- kinematics --------------------------------------------------------------------------------------

void toolPoseAt(WorldHost& h, const Pose2& base, const double* q, Out o) {
  if (!h.pose(base, readConf(q))) return writeNaN(o);
  writePose(h.workspace().toolPose(), o.data());
}
void fToolPose(const rt::CallContext& cx, Args a, Widths, Out o) { toolPoseAt(host(cx), kOrigin, a.data(), o); }
void fToolPoseFrom(const rt::CallContext& cx, Args a, Widths, Out o) {
  toolPoseAt(host(cx), readSe2(a.data()), a.data() + 3, o);
}
void fWithinJointLimits(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = finite(a) && host(cx).scene().withinLimits(readConf(a.data())) ? 1 : 0;
}
void fJointDistance(const rt::CallContext& cx, Args a, Widths, Out o) {
  const world::Scene& s = host(cx).scene();
  double d = 0;
  for (int i = 0; i < world::kArmDof; ++i) {
    const double diff = s.armContinuous(i) ? world::angleDiff(a[i + 7], a[i]) : a[i + 7] - a[i];
    d = std::max(d, std::abs(diff));
  }
  o[0] = std::isfinite(d) ? d : kInf;
}
void fNamedConf(const rt::CallContext& cx, Args a, Widths, Out o) {
  const auto q = host(cx).namedConf(text(cx, a[0]));
  if (!q) return writeNaN(o);
  for (int i = 0; i < world::kArmDof; ++i) o[i] = (*q)[i];
}

// IK for `tool` with the base at `base`, collision-free against the reference world (plus `held` when given).
std::optional<ArmConfig> solveIk(WorldHost& h, const Pose2& base, const Pose3& tool, bool randomSeed, world::Rng& rng,
                                 bool collisionFree, const std::string* held = nullptr) {
  if (!h.pose(base, h.reference().arm, held)) return std::nullopt;
  world::IkOptions o = h.world().ik;
  o.maxAttempts = h.ikAttempts;
  o.requireCollisionFree = collisionFree;
  const ArmConfig seed = randomSeed ? world::randomConfig(h.scene(), rng) : h.reference().arm;
  const world::IkResult r = world::solveIk(h.workspace(), tool, seed, rng, o);
  if (!r.solved()) return std::nullopt;
  return h.scene().normalize(r.q);
}
void fIkExists(const rt::CallContext& cx, Args a, Widths, Out o) {
  world::Rng rng(kQuerySeed);
  o[0] = finite(a) && solveIk(host(cx), kOrigin, readPose(a.data()), false, rng, false) ? 1 : 0;
}
void fIkExistsFrom(const rt::CallContext& cx, Args a, Widths, Out o) {
  world::Rng rng(kQuerySeed);
  o[0] = finite(a) && solveIk(host(cx), readSe2(a.data()), readPose(a.data() + 3), false, rng, false) ? 1 : 0;
}
void fReachableAbove(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  if (!finite(a) || !h.pose(kOrigin, readConf(a.data() + 3))) return;
  const Pose3 tool = h.workspace().toolPose();
  const Eigen::Vector3d target(a[0], a[1], a[2] + a[10]);
  const Eigen::Vector3d z = tool.orientation * Eigen::Vector3d::UnitZ();
  const double tilt = std::acos(std::clamp(-z.z(), -1.0, 1.0));
  o[0] = (tool.position - target).norm() <= 1e-3 && tilt <= 0.01 ? 1 : 0;
}
void writeConf(const ArmConfig& q, Out o) {
  for (int i = 0; i < world::kArmDof; ++i) o[i] = q[i];
}
// The IK samplers start half their draws at the arm's configuration in the reference state (the state the skill
// starts in: the solution on the current branch, closest to the joints, as the reference code takes it) and half
// at random configurations (so repeated draws spread over the solution set).
bool sIkSample(const rt::CallContext& cx, Args a, Widths, rt::Rng& rng, Out o) {
  world::Rng r(rng.next());
  if (!finite(a)) return false;
  const auto q = solveIk(host(cx), kOrigin, readPose(a.data()), r.coin(), r, true);
  if (!q) return false;
  writeConf(*q, o);
  return true;
}
bool sIkSampleFrom(const rt::CallContext& cx, Args a, Widths, rt::Rng& rng, Out o) {
  world::Rng r(rng.next());
  if (!finite(a)) return false;
  const auto q = solveIk(host(cx), readSe2(a.data()), readPose(a.data() + 3), r.coin(), r, true);
  if (!q) return false;
  writeConf(*q, o);
  return true;
}
bool sIkAbove(const rt::CallContext& cx, Args a, Widths, rt::Rng& rng, Out o) {
  world::Rng r(rng.next());
  if (!finite(a)) return false;
  const double yaw = rng.uniform(-M_PI, M_PI);
  const auto q = solveIk(host(cx), kOrigin, toolDown(Eigen::Vector3d(a[0], a[1], a[2] + a[3]), yaw), r.coin(), r, true);
  if (!q) return false;
  writeConf(*q, o);
  return true;
}

// ---- motion ------------------------------------------------------------------------------------------

bool armPlanExists(WorldHost& h, const Pose2& base, const double* from, const double* to) {
  const ArmConfig a = readConf(from), b = readConf(to);
  if (!finite({from, 7}) || !finite({to, 7}) || !h.pose(base, a)) return false;
  world::Rng rng(kQuerySeed);
  world::PlanOptions o = h.world().planning;
  o.maxIterations = h.planIterations;
  return world::planArm(h.workspace(), a, b, rng, o).solved();
}
void fMotionPlanExists(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = armPlanExists(host(cx), kOrigin, a.data(), a.data() + 7) ? 1 : 0;
}
void fMotionPlanExistsFrom(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = finite(a.subspan(0, 3)) && armPlanExists(host(cx), readSe2(a.data()), a.data() + 3, a.data() + 10) ? 1 : 0;
}
void fBasePathExists(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  if (!finite(a) || !h.scene().hasMobileBase() || !h.pose(readSe2(a.data()), h.reference().arm)) return;
  world::Rng rng(kQuerySeed);
  world::PlanOptions p = h.world().planning;
  p.maxIterations = h.planIterations;
  o[0] = world::planBase(h.workspace(), readSe2(a.data() + 3), rng, p).solved() ? 1 : 0;
}

// ---- collision ---------------------------------------------------------------------------------------

bool collisionFree(WorldHost& h, const Pose2& base, const double* q, const std::string* held = nullptr) {
  if (!finite({q, 7}) || !h.pose(base, readConf(q), held)) return false;
  return world::checkRobotCollisions(h.workspace(), h.world().planning.collision).free();
}
void fConfCollisionFree(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = collisionFree(host(cx), kOrigin, a.data()) ? 1 : 0;
}
void fConfCollisionFreeFrom(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = finite(a.subspan(0, 3)) && collisionFree(host(cx), readSe2(a.data()), a.data() + 3) ? 1 : 0;
}
void fConfCollisionFreeHolding(const rt::CallContext& cx, Args a, Widths, Out o) {
  const std::string held = text(cx, a[10]);
  o[0] = finite(a.subspan(0, 3)) && collisionFree(host(cx), readSe2(a.data()), a.data() + 3, &held) ? 1 : 0;
}
void fBaseCollisionFree(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] =
      finite(a) && h.scene().hasMobileBase() && collisionFree(h, readSe2(a.data()), h.reference().arm.data()) ? 1 : 0;
}
void fCollisionFreeIkExists(const rt::CallContext& cx, Args a, Widths, Out o) {
  world::Rng rng(kQuerySeed);
  const std::string held = text(cx, a[10]);
  o[0] =
      finite(a.subspan(0, 10)) && solveIk(host(cx), readSe2(a.data()), readPose(a.data() + 3), false, rng, true, &held)
          ? 1
          : 0;
}

// ---- scene queries -----------------------------------------------------------------------------------

void fBodyPose(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string name = text(cx, a[0]);
  if (const auto p = referencePose(h, name)) return writePose(*p, o.data());
  const int body = h.scene().bodyId(name);
  if (body < 0) return writeNaN(o);
  h.pose(h.reference().base, h.reference().arm);
  writePose(h.workspace().bodyPose(body), o.data());
}
void fSitePose(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  h.pose(h.reference().base, h.reference().arm);
  const auto p = h.workspace().sitePose(text(cx, a[0]));
  if (!p) return writeNaN(o);
  writePose(*p, o.data());
}
void fSupportSurface(const rt::CallContext& cx, Args a, Widths, Out o) {
  const std::string surface = host(cx).supportSurface(text(cx, a[0]));
  o[0] = static_cast<double>(cx.strings->intern(surface));
}
void fApproachBase(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  std::string target = text(cx, a[0]);
  if (h.scene().siteId("approach_" + target) < 0) target = h.supportSurface(target);
  const int site = target.empty() ? -1 : h.scene().siteId("approach_" + target);
  if (site < 0) return writeNaN(o);
  h.pose(h.reference().base, h.reference().arm);
  const Pose3 p = h.workspace().sitePose(site);
  const Eigen::Vector3d x = p.orientation * Eigen::Vector3d::UnitX();
  o[0] = p.position.x();
  o[1] = p.position.y();
  o[2] = std::atan2(x.y(), x.x());
}
void fToolPoseForObject(const rt::CallContext& cx, Args a, Widths, Out o) {
  const auto grasp = host(cx).nominalGrasp(text(cx, a[0]));
  if (!grasp || !finite(a.subspan(1, 7))) return writeNaN(o);
  writePose(readPose(a.data() + 1) * grasp->inverse(), o.data());
}
void fWipeStartPose(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string tool = text(cx, a[0]);
  const auto grasp = h.nominalGrasp(tool);
  if (!grasp || !finite(a.subspan(2, 3))) return writeNaN(o);
  const auto p = world::preWipeToolPose(h.world(), text(cx, a[1]), tool, *grasp, readSe2(a.data() + 2));
  if (!p) return writeNaN(o);
  writePose(*p, o.data());
}
void fStandardGraspPose(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string body = text(cx, a[0]);
  const double k = a[1];
  const auto p = referencePose(h, body);
  const auto inBody = std::isfinite(k) && k == std::floor(k) && std::abs(k) < 1e6
                          ? actions::standardGraspInBody(body, static_cast<int>(k))
                          : std::nullopt;
  if (!p || !inBody) return writeNaN(o);
  writePose(*p * *inBody, o.data());
}
void fSideGraspPose(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string body = text(cx, a[0]);
  const auto p = referencePose(h, body);
  const auto g = p ? h.sideGrasp(body, *p, a[1]) : std::nullopt;
  if (!g) return writeNaN(o);
  writePose(*g, o.data());
}

// ---- objects -----------------------------------------------------------------------------------------

double bodyDistance(WorldHost& h, const std::string& a, const Pose3& pa, const std::string& b, const Pose3& pb) {
  const double d = h.world().clearance().objectDistance(a, pa, b, pb);
  return d < 0 ? kNaN : d;
}
void fBodiesApart(const rt::CallContext& cx, Args a, Widths, Out o) {
  o[0] = finite(a) && bodyDistance(host(cx), text(cx, a[0]), readPose(a.data() + 1), text(cx, a[8]),
                                   readPose(a.data() + 9)) > 0
             ? 1
             : 0;
}
void fBodiesApartAtXY(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  const std::string na = text(cx, a[0]), nb = text(cx, a[3]);
  auto pa = referencePose(h, na), pb = referencePose(h, nb);
  if (!pa || !pb || !finite(a)) return;
  pa->position.x() = a[1];
  pa->position.y() = a[2];
  pb->position.x() = a[4];
  pb->position.y() = a[5];
  o[0] = bodyDistance(h, na, *pa, nb, *pb) > 0 ? 1 : 0;
}
void fSupportedAtXY(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  const std::string body = text(cx, a[0]);
  auto p = referencePose(h, body);
  if (!p || !finite(a.subspan(1, 2))) return;
  p->position.x() = a[1];
  p->position.y() = a[2];
  if (!h.pose(h.reference().base, h.reference().arm)) return;
  o[0] = world::supportAt(h.workspace(), body, *p).supported() ? 1 : 0;
}
void fBodyClearance(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string body = text(cx, a[0]);
  o[0] = kInf;
  if (h.scene().objectIndex(body) < 0 || !finite(a)) return;
  const Pose3 p = readPose(a.data() + 1);
  for (const auto& other : h.scene().objects()) {
    if (other.name == body) continue;
    if (h.reference().held && h.reference().held->object == other.name) continue;
    const auto q = referencePose(h, other.name);
    if (q) o[0] = std::min(o[0], h.world().clearance().objectDistance(body, p, other.name, *q));
  }
}
void fRestsOn(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  if (!finite(a.subspan(1, 7))) return;
  const auto fp = h.footprint(text(cx, a[0]), readPose(a.data() + 1));
  const auto top = h.surfaceTop(text(cx, a[8]));
  if (!fp || !top) return;
  const bool onTop = std::abs(fp->bottom - top->center.z()) <= 0.01;
  const bool inside = std::abs(fp->centerX - top->center.x()) + fp->halfX <= top->halfX + 1e-9 &&
                      std::abs(fp->centerY - top->center.y()) + fp->halfY <= top->halfY + 1e-9;
  o[0] = onTop && inside ? 1 : 0;
}
void fPlacementClear(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = 0;
  if (!finite(a.subspan(1, 8))) return;
  h.pose(h.reference().base, h.reference().arm);
  world::PlacementOptions p;
  p.clearance = a[8];
  o[0] = h.world().clearance().checkPlacement(h.workspace(), text(cx, a[0]), readPose(a.data() + 1), p).ok() ? 1 : 0;
}
bool sPlacementOn(const rt::CallContext& cx, Args a, Widths, rt::Rng& rng, Out o) {
  WorldHost& h = host(cx);
  const auto top = h.surfaceTop(text(cx, a[0]));
  const std::string body = text(cx, a[1]);
  const double yaw = a[2];
  if (!top || !std::isfinite(yaw)) return false;
  Pose3 p;
  p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  const auto fp = h.footprint(body, p);  // at the origin: offsets of the footprint from the body frame
  if (!fp || fp->halfX > top->halfX || fp->halfY > top->halfY) return false;
  const double cx0 = rng.uniform(top->center.x() - top->halfX + fp->halfX, top->center.x() + top->halfX - fp->halfX);
  const double cy0 = rng.uniform(top->center.y() - top->halfY + fp->halfY, top->center.y() + top->halfY - fp->halfY);
  p.position = Eigen::Vector3d(cx0 - fp->centerX, cy0 - fp->centerY, top->center.z() - fp->bottom);
  writePose(p, o.data());
  return true;
}

// ---- occlusion ---------------------------------------------------------------------------------------

double occlusionNow(WorldHost& h) {
  if (!h.world().occlusion()) return 0.0;
  return world::occlusionScore(h.workspace(), *h.world().occlusion());
}
void fOcclusion(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = finite(a) && h.pose(h.reference().base, readConf(a.data())) ? occlusionNow(h) : kNaN;
}
void fOcclusionHolding(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  const std::string held = text(cx, a[7]);
  o[0] = finite(a.subspan(0, 7)) && h.pose(h.reference().base, readConf(a.data()), &held) ? occlusionNow(h) : kNaN;
}
void fOcclusionByBody(const rt::CallContext& cx, Args a, Widths, Out o) {
  WorldHost& h = host(cx);
  o[0] = kNaN;
  if (!finite(a.subspan(1, 7)) || !h.pose(h.reference().base, h.reference().arm)) return;
  if (!h.moveObject(text(cx, a[0]), readPose(a.data() + 1))) return;
  o[0] = occlusionNow(h);
}

// `state`: the result depends on the reference state (objects, held body, the arm or base as observed), not only
// on the arguments and the scene's fixed geometry; such calls are evaluated in the state of their skill.
struct FunctionEntry {
  const char* name;
  rt::FunctionImpl impl;
  bool state;
};
struct SamplerEntry {
  const char* name;
  rt::SamplerImpl impl;
  bool state;
};

constexpr FunctionEntry kFunctions[] = {
    {"toolPose", fToolPose, false},
    {"toolPoseFrom", fToolPoseFrom, false},
    {"withinJointLimits", fWithinJointLimits, false},
    {"jointDistance", fJointDistance, false},
    {"namedConf", fNamedConf, false},
    {"ikExists", fIkExists, true},  // seeded at the observed arm
    {"ikExistsFrom", fIkExistsFrom, true},
    {"reachableAbove", fReachableAbove, false},
    {"motionPlanExists", fMotionPlanExists, true},
    {"motionPlanExistsFrom", fMotionPlanExistsFrom, true},
    {"basePathExists", fBasePathExists, true},
    {"bodyPose", fBodyPose, true},
    {"sitePose", fSitePose, true},
    {"supportSurface", fSupportSurface, true},
    {"approachBase", fApproachBase, true},
    {"toolPoseForObject", fToolPoseForObject, true},
    {"wipeStartPose", fWipeStartPose, true},
    {"confCollisionFree", fConfCollisionFree, true},
    {"confCollisionFreeFrom", fConfCollisionFreeFrom, true},
    {"confCollisionFreeHolding", fConfCollisionFreeHolding, true},
    {"baseCollisionFree", fBaseCollisionFree, true},
    {"collisionFreeIkExists", fCollisionFreeIkExists, true},
    {"bodiesApart", fBodiesApart, false},
    {"bodiesApartAtXY", fBodiesApartAtXY, true},
    {"supportedAtXY", fSupportedAtXY, true},
    {"bodyClearance", fBodyClearance, true},
    {"restsOn", fRestsOn, false},
    {"placementClear", fPlacementClear, true},
    {"sideGraspPose", fSideGraspPose, true},
    {"standardGraspPose", fStandardGraspPose, true},
    {"occlusion", fOcclusion, true},
    {"occlusionHolding", fOcclusionHolding, true},
    {"occlusionByBody", fOcclusionByBody, true},
};
constexpr SamplerEntry kSamplers[] = {
    {"ikSample", sIkSample, true},
    {"ikSampleFrom", sIkSampleFrom, true},
    {"ikAbove", sIkAbove, true},
    {"placementOn", sPlacementOn, false},
};

}  // namespace

rt::Builtins withWorld(rt::Builtins builtins, std::shared_ptr<const world::Scene> scene,
                       const WorldBuiltinOptions& options) {
  auto h = std::make_shared<WorldHost>(std::move(scene));
  h->planIterations = options.planIterations;
  h->ikAttempts = options.ikAttempts;
  for (const auto& f : kFunctions) builtins.addFunction(f.name, f.impl, f.state);
  for (const auto& s : kSamplers) builtins.addSampler(s.name, s.impl, s.state);
  builtins.setHost(std::move(h));
  return builtins;
}

bool addWorldFromFile(rt::Builtins& builtins, const std::string& path, std::string& error,
                      const WorldBuiltinOptions& options) {
  const world::SceneLoadResult r = world::Scene::loadFile(path);
  if (r.status != world::LoadStatus::Ok) {
    error = r.message;
    return false;
  }
  builtins = withWorld(std::move(builtins), r.scene, options);
  return true;
}

bool setWorldReference(rt::BuiltinHost* host, const world::WorldState& state) {
  auto* h = dynamic_cast<WorldHost*>(host);
  return h != nullptr && h->setReference(state);
}

bool setWorldExecutor(rt::BuiltinHost* host, std::shared_ptr<const actions::RobotActions> executor) {
  auto* h = dynamic_cast<WorldHost*>(host);
  if (h == nullptr || !executor) return false;
  h->setExecutor(std::move(executor));
  return true;
}

std::vector<std::string> worldBuiltinNames() {
  std::vector<std::string> out;
  for (const auto& f : kFunctions) out.emplace_back(f.name);
  for (const auto& s : kSamplers) out.emplace_back(s.name);
  return out;
}

}  // namespace cbtl::bind
