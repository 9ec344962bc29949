// One of the translation units that include FCL (slow to compile): the audit asks FCL directly, not through the
// executor's geometry.
#include "app/audit/MotionAudit.h"

#include "app/LoadedProgram.h"
#include "app/audit/RecordContinuity.h"
#include "robot/actions/ClearanceExceptions.h"
#include "robot/world/FclShapes.h"
#include "robot/world/MotionRecord.h"
#include "robot/world/Workspace.h"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fmt/core.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <set>

namespace cbtl::app {

namespace {

using json = nlohmann::json;
// Metres the held object may sink into the face it rests on while it is lifted off or set down (the executor's
// robot/actions kRestingContact, restated: the audit does not read the executor's constants).
constexpr double kRestingContact = 0.001;
// Metres the gripper's pads may sink into what they hold (robot/world GraspClosure.h kGraspCompliance, restated).
constexpr double kGripCompliance = 0.001;
constexpr const char* kGripClass = "grip";  // the held object against the gripper that holds it
constexpr double kGripTouch = 1e-4;         // metres: a finger this near what it holds touches it
// Metres a GJK distance of FCL may be off (its default tolerance is 1e-6 m; ten times that, to be safe).
constexpr double kDistanceTolerance = 1e-5;
using world::BodyKind;

struct AuditPair {
  int g1, g2;
  double required;
  int bodyClass;  // of the pair (person, scenery, objects, self), an index of Auditor::classes_
  // The pair is not measured while odometer(g1) + odometer(g2) < skipBelow: at the state where it was last measured
  // its distance exceeded what could matter by skipBelow minus the odometers' sum then (see Auditor::travel).
  double skipBelow = -std::numeric_limits<double>::infinity();
};

class Auditor {
 public:
  Auditor(std::shared_ptr<const world::Scene> scene, const AuditOptions& o, AuditReport& report)
      : scene_(std::move(scene)), ws_(scene_), options_(o), report_(report) {
    const mjModel* m = scene_->model();
    for (int g = 0; g < m->ngeom; ++g) shapes_.push_back(world::fclShapeOf(m, g));
    odometer_.assign(static_cast<std::size_t>(m->ngeom), 0.0);
    lastPos_.assign(static_cast<std::size_t>(3 * m->ngeom), 0.0);
    lastRot_.assign(static_cast<std::size_t>(9 * m->ngeom), 0.0);
  }

  // The closest approach of every class, into the report (kept in a table while auditing: looked up per pair).
  void finish() {
    for (std::size_t c = 0; c < classes_.size(); ++c)
      if (!closest_[c].where.empty()) report_.closest[classes_[c]] = closest_[c];
  }

  // Checks one recorded motion; `where` names it in the report. `declared`: the allowances the call's `allow`
  // blocks grant; every allowance of the record must be one of them or a resting contact.
  // A motion that did not start where the record's previous one left the robot (RecordContinuity).
  void gap(const std::string& where, double distance) {
    addViolation(where, "", "", distance, kContinuityTolerance,
                 fmt::format("the robot moved by {:.4g} (rad or m) since the previous motion without a recorded motion",
                             distance));
  }

  void audit(const world::ExecutedMotion& motion, const std::vector<world::ContactAllowance>& declared,
             const std::string& where) {
    if (ws_.setState(motion.start) != world::StateStatus::Ok) {
      addViolation(where, "", "", 0, 0, "the recorded start state is not a valid state of the scene");
      return;
    }
    for (const world::ContactAllowance& a : motion.allowances) {
      // The one contact actions allow on their own: the held object on the face it is lifted from or set onto.
      const bool resting = a.part == world::ContactAllowance::Part::HeldObject && a.separation >= -kRestingContact;
      if (!resting && std::find(declared.begin(), declared.end(), a) == declared.end())
        addViolation(where, world::toString(a.part), a.geom >= 0 ? scene_->geomName(a.geom) : scene_->bodyName(a.body),
                     0, a.separation, "the record allows an approach no `allow` of the call declares");
    }
    ++report_.motions;
    pairs(motion);
    if (ws_.heldObject() >= 0) checkGrip(where);
    if (motion.kind == world::ExecutedMotion::Kind::Arm) {
      for (std::size_t i = 0; i + 1 < motion.arm.size(); ++i)
        armSegment(motion.arm[i], motion.arm[i + 1], i == 0, where);
    } else {
      for (std::size_t i = 0; i + 1 < motion.base.size(); ++i)
        baseSegment(motion.base[i], motion.base[i + 1], i == 0, where);
    }
  }

 private:
  bool isRobot(int body) const {
    const BodyKind k = scene_->bodyKind(body);
    return k == BodyKind::Robot || k == BodyKind::Gripper;
  }
  bool isHeld(int body) const { return ws_.heldObject() >= 0 && scene_->objectOfBody(body) == ws_.heldObject(); }

  // The pairs a motion must respect, from the scene's candidate pairs: robot and held object against the rest;
  // then the held object against the gripper holding it (class "grip").
  void pairs(const world::ExecutedMotion& motion) {
    const mjModel* m = scene_->model();
    pairs_.clear();
    moving_.clear();
    freshMotion_ = true;
    auto add = [&](int g1, int g2, double keepOut) {
      const int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
      const bool moving1 = isRobot(b1) || isHeld(b1), moving2 = isRobot(b2) || isHeld(b2);
      if (!moving1 && !moving2) return;
      if ((isHeld(b1) && (isHeld(b2) || scene_->bodyKind(b2) == BodyKind::Gripper)) ||
          (isHeld(b2) && scene_->bodyKind(b1) == BodyKind::Gripper))
        return;
      if (!moving1) std::swap(g1, g2);
      const int other = m->geom_bodyid[g2];
      double required = keepOut;
      for (const world::ContactAllowance& a : motion.allowances) {
        const int moving = m->geom_bodyid[g1];
        const bool partOk = a.part == world::ContactAllowance::Part::HeldObject ? isHeld(moving)
                            : a.part == world::ContactAllowance::Part::Gripper
                                ? scene_->bodyKind(moving) == BodyKind::Gripper
                                : isRobot(moving);
        const bool named = g2 == a.geom || (a.geom < 0 && other == a.body);
        if (partOk && named) required = std::min(required, a.separation);
      }
      const world::BodyClearance* declared = scene_->clearanceOfBody(other);
      std::string cls = isRobot(other) || isHeld(other)               ? "self"
                        : declared != nullptr                         ? declared->name
                        : scene_->bodyKind(other) == BodyKind::Object ? "objects"
                                                                      : "scenery";
      // Approaches a skill declared are reported apart: the class's own figure is what held without exceptions.
      if (required < keepOut) cls += kUnderAllow;
      pairs_.push_back({g1, g2, required, classIndex(cls)});
      for (int g : {g1, g2})
        if (isRobot(m->geom_bodyid[g]) || isHeld(m->geom_bodyid[g])) moving_.push_back(g);
    };
    for (const auto& p : scene_->robotPairs()) add(p.g1, p.g2, p.margin);
    for (const auto& p : scene_->selfPairs()) add(p.g1, p.g2, p.margin);
    if (ws_.heldObject() >= 0) {
      for (const auto& p : scene_->objectPairs(ws_.heldObject())) add(p.g1, p.g2, p.margin);
    }
    std::sort(moving_.begin(), moving_.end());
    moving_.erase(std::unique(moving_.begin(), moving_.end()), moving_.end());
  }

  int classIndex(const std::string& name) {
    const auto known = std::find(classes_.begin(), classes_.end(), name);
    if (known != classes_.end()) return static_cast<int>(known - classes_.begin());
    classes_.push_back(name);
    closest_.push_back({options_.cap, "", "", ""});
    return static_cast<int>(classes_.size()) - 1;
  }

  // Adds to each moving geom's odometer a bound on how far any point of it moved since the previous state: its
  // centre's displacement plus its bounding radius times the change of its rotation (|(R' - R) v| <= |R' - R|_F |v|
  // for every point v of the geom, |v| <= its bounding radius). Measured on the states themselves, so a pair's
  // distance at this state is at least its distance where it was last measured minus the sum of its geoms'
  // odometer readings since: a pair far from mattering is skipped until its geoms have travelled that far.
  void travel() {
    const mjModel* m = scene_->model();
    const mjData* d = ws_.data();
    for (int g : moving_) {
      const double* x = d->geom_xpos + 3 * g;
      const double* r = d->geom_xmat + 9 * g;
      double* px = lastPos_.data() + 3 * g;
      double* pr = lastRot_.data() + 9 * g;
      if (!freshMotion_) {
        double rot = 0;
        for (int k = 0; k < 9; ++k) rot += (r[k] - pr[k]) * (r[k] - pr[k]);
        odometer_[static_cast<std::size_t>(g)] +=
            std::hypot(x[0] - px[0], x[1] - px[1], x[2] - px[2]) + m->geom_rbound[g] * std::sqrt(rot);
      }
      std::copy(x, x + 3, px);
      std::copy(r, r + 9, pr);
    }
    freshMotion_ = false;
  }
  static bool solid(const mjModel* m, int g) { return (m->geom_contype[g] | m->geom_conaffinity[g]) != 0; }

  // The grip of a held object: each finger touches it, and no part of the gripper presses into it beyond the pads'
  // compliance. Checked once per motion: a record's held object and gripper opening are fixed in the gripper's frame
  // for the whole motion, so every state of it has the same grip.
  void checkGrip(const std::string& where) {
    const mjModel* m = scene_->model();
    std::vector<int> held;
    for (int h = 0; h < m->ngeom; ++h)
      if (solid(m, h) && isHeld(m->geom_bodyid[h])) held.push_back(h);
    for (int g = 0; g < m->ngeom; ++g) {
      if (!solid(m, g) || scene_->bodyKind(m->geom_bodyid[g]) != BodyKind::Gripper) continue;
      double nearest = std::numeric_limits<double>::infinity();
      int at = -1;
      for (int h : held) {
        const double sep = separation(g, h);
        if (sep < nearest) nearest = sep, at = h;
      }
      if (at < 0) continue;
      // The class's figure is the deepest press of the run.
      const auto known = report_.closest.find(kGripClass);
      if (known == report_.closest.end() || nearest < known->second.distance)
        report_.closest[kGripClass] = {nearest, where, scene_->geomName(g), scene_->geomName(at)};
      if (nearest < -kGripCompliance)
        addViolation(where, scene_->geomName(g), scene_->geomName(at), nearest, -kGripCompliance,
                     "the gripper presses into what it holds beyond the pads' compliance");
      const bool finger = m->geom_bodyid[g] != scene_->endEffectorBody();
      if (finger && nearest > kGripTouch)
        addViolation(where, scene_->geomName(g), scene_->geomName(at), nearest, kGripTouch,
                     "a finger does not touch what the gripper holds");
    }
  }

  void armSegment(const world::ArmConfig& a, const world::ArmConfig& b, bool first, const std::string& where) {
    ++report_.segments;
    world::ArmConfig step{};
    double linf = 0;
    for (int i = 0; i < world::kArmDof; ++i) {
      step[i] = scene_->armContinuous(i) ? world::angleDiff(b[i], a[i]) : b[i] - a[i];
      linf = std::max(linf, std::abs(step[i]));
    }
    const long n = std::max(1L, static_cast<long>(std::ceil(linf / options_.resolution)));
    for (long k = first ? 0 : 1; k <= n; ++k) {
      world::ArmConfig q{};
      const double t = static_cast<double>(k) / static_cast<double>(n);
      for (int i = 0; i < world::kArmDof; ++i) q[i] = k == n ? b[i] : a[i] + t * step[i];
      ws_.setArm(q);
      checkState(where);
    }
  }

  void baseSegment(const world::Pose2& a, const world::Pose2& b, bool first, const std::string& where) {
    ++report_.segments;
    const double dx = b.x - a.x, dy = b.y - a.y, dyaw = world::angleDiff(b.yaw, a.yaw);
    const double linf = std::max({std::abs(dx), std::abs(dy), std::abs(dyaw)});
    const long n = std::max(1L, static_cast<long>(std::ceil(linf / options_.resolution)));
    for (long k = first ? 0 : 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(n);
      ws_.setBase(k == n ? b : world::Pose2{a.x + t * dx, a.y + t * dy, world::wrapAngle(a.yaw + t * dyaw)});
      checkState(where);
    }
  }

  fcl::Transform3d transform(int g) const { return world::geomWorldTransform(ws_.data(), g); }

  // FCL's separation of a pair: its distance, or minus the deepest contact when they collide.
  double separation(int g1, int g2) const {
    const auto& s1 = shapes_[static_cast<std::size_t>(g1)];
    const auto& s2 = shapes_[static_cast<std::size_t>(g2)];
    const fcl::Transform3d t1 = transform(g1), t2 = transform(g2);
    fcl::CollisionRequestd creq(4, true);
    creq.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd cres;
    if (fcl::collide(s1.get(), t1, s2.get(), t2, creq, cres) > 0) {
      double depth = 0;
      for (std::size_t i = 0; i < cres.numContacts(); ++i)
        depth = std::max(depth, cres.getContact(i).penetration_depth);
      return -depth;
    }
    fcl::DistanceRequestd dreq;
    dreq.gjk_solver_type = fcl::GST_INDEP;
    fcl::DistanceResultd dres;
    return std::max(0.0, fcl::distance(s1.get(), t1, s2.get(), t2, dreq, dres));
  }

  // A lower bound on the pair's distance, to skip pairs that cannot matter: bounding spheres, and for a box or a
  // plane its true extent against the other's bounding sphere (a plane: the height of the other's centre).
  double quickBound(int g1, int g2) const {
    const mjModel* m = scene_->model();
    const mjData* d = ws_.data();
    const double r1 = m->geom_rbound[g1], r2 = m->geom_rbound[g2];
    const double* x1 = d->geom_xpos + 3 * g1;
    const double* x2 = d->geom_xpos + 3 * g2;
    double bound = -std::numeric_limits<double>::infinity();
    if (r1 > 0 && r2 > 0) bound = std::hypot(x1[0] - x2[0], x1[1] - x2[1], x1[2] - x2[2]) - r1 - r2;
    for (const auto& [solid, other] : {std::pair{g1, g2}, std::pair{g2, g1}}) {
      const double radius = m->geom_rbound[other];
      if (radius <= 0) continue;
      const double* c = d->geom_xpos + 3 * solid;
      const double* r = d->geom_xmat + 9 * solid;
      const double* x = d->geom_xpos + 3 * other;
      const double v[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
      if (m->geom_type[solid] == mjGEOM_PLANE) {
        bound = std::max(bound, r[2] * v[0] + r[5] * v[1] + r[8] * v[2] - radius);
      } else if (m->geom_type[solid] == mjGEOM_BOX) {
        double outside = 0;
        for (int k = 0; k < 3; ++k) {
          const double e = std::abs(r[k] * v[0] + r[3 + k] * v[1] + r[6 + k] * v[2]) - m->geom_size[3 * solid + k];
          if (e > 0) outside += e * e;
        }
        bound = std::max(bound, std::sqrt(outside) - radius);
      }
    }
    return bound;
  }

  void checkState(const std::string& where) {
    ++report_.states;
    travel();
    for (AuditPair& p : pairs_) {
      if (!shapes_[static_cast<std::size_t>(p.g1)] || !shapes_[static_cast<std::size_t>(p.g2)]) continue;
      const double travelled = odometer_[static_cast<std::size_t>(p.g1)] + odometer_[static_cast<std::size_t>(p.g2)];
      if (options_.skipFarPairs && travelled < p.skipBelow) continue;
      // Measured when it could be a violation, or nearer than the class's closest approach so far (within the cap).
      ClosestApproach& closest = closest_[static_cast<std::size_t>(p.bodyClass)];
      const double reportable = std::min(closest.distance, options_.cap);
      const double matters = std::max(std::max(p.required, 0.0), reportable);
      const double bound = quickBound(p.g1, p.g2);
      if (bound > matters) {
        // What matters only shrinks as the audit goes on, so the skip stays sound.
        p.skipBelow = travelled + (bound - matters);
        continue;
      }
      const double sep = separation(p.g1, p.g2);
      if (sep < reportable) closest = {sep, where, scene_->geomName(p.g1), scene_->geomName(p.g2)};
      const bool violated = p.required >= 0 ? (sep < p.required || sep <= 0) : sep < p.required;
      if (violated) addViolation(where, scene_->geomName(p.g1), scene_->geomName(p.g2), sep, p.required, "");
      // The measured distance is the tightest bound: the pair rests until its geoms could have closed the gap (less
      // kDistanceTolerance, for GJK's own).
      const double slack =
          sep - kDistanceTolerance - std::max(std::max(p.required, 0.0), std::min(closest.distance, options_.cap));
      if (slack > 0) p.skipBelow = travelled + slack;
    }
  }

  void addViolation(const std::string& where, std::string first, std::string second, double sep, double required,
                    const std::string& note) {
    ++report_.violationCount;
    if (report_.violations.size() < options_.listed)
      report_.violations.push_back(
          {note.empty() ? where : where + ": " + note, std::move(first), std::move(second), sep, required});
  }

  std::shared_ptr<const world::Scene> scene_;
  world::Workspace ws_;
  AuditOptions options_;
  AuditReport& report_;
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> shapes_;
  std::vector<AuditPair> pairs_;
  std::vector<std::string> classes_;       // the pair classes met so far; closest_ is indexed alike
  std::vector<ClosestApproach> closest_;   // each class's closest approach (the cap while nothing came nearer)
  std::vector<int> moving_;                // the geoms of this motion's pairs that move with the robot
  std::vector<double> odometer_;           // per geom: the bound on its points' travel summed over the states
  std::vector<double> lastPos_, lastRot_;  // per geom: its position and rotation at the previous state
  bool freshMotion_ = true;                // the next state starts a motion: no travel from the previous one
};

// The whole content of a gzip file (any number of members) or of a plain file (zlib reads those as they are).
bool readMaybeGzipped(const std::string& path, std::string& out) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) return false;
  char buf[1 << 16];
  int n = 0;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  const bool ok = n == 0;
  gzclose(f);
  return ok;
}

// The exceptions the recorded call carried (runtime/approach/Checkpoint.h writes them as "allow").
std::vector<sim::ClearanceException> exceptionsOf(const json& line) {
  std::vector<sim::ClearanceException> out;
  if (!line.contains("call") || !line.at("call").contains("allow")) return out;
  for (const json& e : line.at("call").at("allow"))
    out.push_back({e.at("part").get<std::string>(), e.at("names").get<std::vector<std::string>>(),
                   e.at("separation").get<double>(), e.value("declared_at", std::string())});
  return out;
}

std::string describe(const json& line) {
  std::string call = line.value("call", json::object()).value("name", std::string("?"));
  std::string where = fmt::format("{} step {}", line.value("phase", std::string("?")), line.value("step", -1));
  if (line.contains("task")) where += fmt::format(" task {}", line["task"].get<int>());
  return where + ": " + call;
}

}  // namespace

AuditReport auditRun(const std::string& runDir, const AuditOptions& options) {
  namespace fs = std::filesystem;
  AuditReport report;
  report.run = runDir;
  std::string program = options.program;
  if (program.empty()) {
    std::ifstream in(fs::path(runDir) / "config.json");
    if (!in) {
      report.error = fmt::format("{}: no config.json: not a run folder", runDir);
      return report;
    }
    try {
      program = json::parse(in).value("file", std::string());
    } catch (const json::exception& e) {
      report.error = fmt::format("{}/config.json: {}", runDir, e.what());
      return report;
    }
  }
  const auto loaded = LoadedProgram::load(program);
  if (!loaded->ok() || !loaded->scene()) {
    report.error = fmt::format("{}: cannot load the run's program '{}' (pass --program FILE){}", runDir, program,
                               loaded->ok() ? ": it has no world scene" : "");
    return report;
  }
  // The run writes motions.jsonl.gz; a plain motions.jsonl (written by hand, or unpacked) is read the same way.
  std::string name = "motions.jsonl.gz";
  if (!fs::exists(fs::path(runDir) / name)) name = "motions.jsonl";
  std::string all;
  if (!readMaybeGzipped((fs::path(runDir) / name).string(), all)) {
    report.error = fmt::format("{}: no readable motions.jsonl.gz (the run recorded no motions)", runDir);
    return report;
  }
  std::vector<std::string> classes;
  for (const auto& c : loaded->scene()->clearances()) classes.push_back(c.name);
  for (const char* c : {"scenery", "objects", "self"}) classes.push_back(c);
  for (const std::string& c : classes) {
    report.classes.push_back(c);
    report.classes.push_back(c + kUnderAllow);
  }
  report.classes.push_back(kGripClass);
  Auditor auditor(loaded->scene(), options, report);
  RecordContinuity continuity(*loaded->scene());
  auto tally = [&] {
    report.continuityChecked = continuity.checked();
    const PlanTally& t = continuity.tally();
    report.gaps = t.gaps;
    report.plans = t.plans;
    report.dryRunPlans = t.dryRun;
    report.dryRunPlansRejected = t.dryRunRejected;
    auditor.finish();
  };
  std::size_t at = 0;
  for (long number = 1; at < all.size(); ++number) {
    std::size_t end = all.find('\n', at);
    if (end == std::string::npos) end = all.size();
    const std::string text = all.substr(at, end - at);
    at = end + 1;
    if (text.empty()) continue;
    try {
      const json line = json::parse(text);
      const std::string phase = line.value("phase", std::string("?"));
      if (line.contains("reset")) {
        continuity.reset(phase);
        continue;
      }
      if (line.contains("plan")) {
        continuity.plan(phase, line.at("plan").value("dry_run", false));
        continue;
      }
      std::vector<world::ContactAllowance> declared;
      std::string error;
      if (!actions::resolveClearanceExceptions(*loaded->scene(), exceptionsOf(line), declared, error))
        throw std::runtime_error(error);
      const world::ExecutedMotion motion = world::motionFromJson(*loaded->scene(), line.at("motion").dump());
      const std::int64_t before = report.violationCount;
      auditor.audit(motion, declared, describe(line));
      const double gap = continuity.motion(phase, motion, report.violationCount > before);
      if (gap > kContinuityTolerance) auditor.gap(describe(line), gap);
    } catch (const std::exception& e) {
      report.error = fmt::format("{}/{}:{}: {}", runDir, name, number, e.what());
      tally();
      return report;
    }
  }
  tally();
  return report;
}

}  // namespace cbtl::app
