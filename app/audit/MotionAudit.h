// MotionAudit.h — `cbtl audit`: re-checks every motion a run recorded (the run folder's motions.jsonl,
// robot/world/MotionRecord.h) without the code that planned and certified it.
//
// An independent path on purpose: the executor proves segments with motion bounds and its own exact geometry
// (robot/world/SegmentCertificate.h, GeomDistance.h); the audit samples every segment densely (at most
// `resolution` rad, or metres for the base, between samples, L∞) and asks FCL 0.7 directly about every candidate
// pair near enough to matter (collision with contact depth, distance), comparing each pair with the separation
// it must keep: the scene's keep-out (MJCF margin or <pair> margin), 0 otherwise (touching is contact), or minus
// the depth of an allowance the motion's record declares. It shares with the executor only the scene's data: the
// geoms, the candidate pairs MuJoCo's filters give, the keep-outs and the FCL shape of each geom.
//
// Body classes: the program's clearances (`clearance person: "user" >= 5 cm;`: the pairs with a body of the class,
// which must keep its distance unless the motion's record declares an exception), then self (robot × robot and the
// held object × the arm), objects (movable objects not held) and scenery (everything else). Pairs whose requirement
// an exception of the motion lowered (a skill's `allow`) count in a class of their own, "<class> under an allow":
// the closest approach of a class is what held where no exception applied. Last, "grip": the gripper's fingers and
// palm against the object they hold, which may press in by the pads' compliance (1 mm, robot/world GraspClosure.h)
// and no further; its "closest approach" is the deepest press (negative).
// Speed without a weaker check: a pair is measured only where it could matter (a violation, or nearer than its
// class's closest approach so far, within the cap). A cheap lower bound (bounding spheres, a box's or plane's true
// extent) or the last measured distance says how far a pair is from mattering; the pair then rests until its geoms
// could have closed that gap, by an odometer of each moving geom summed over the sampled states (its centre's
// displacement plus its bounding radius times |R' - R|_F: no point of it moved more). The report is the same as when
// every pair is measured at every state (`skipFarPairs = false`, `cbtl audit --every-pair`; a test compares them).
// The record's plans and resets (runtime/approach/RunDirectory.h) let it check that the robot moved by no motion it
// did not see, and count the plans a dry run accepted that it rejects (app/audit/RecordContinuity.h).
// Units: metres, radians.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cbtl::app {

struct AuditOptions {
  double resolution = 0.002;  // largest step between sampled states (rad for joints and yaw, m for the base)
  double cap = 0.10;          // distances up to this are measured for the clearance report (m)
  bool skipFarPairs = true;   // false: every candidate pair is measured at every sampled state (slower, same report)
  std::size_t listed = 20;    // violations listed in the report (all are counted)
  std::string program;        // the .cbtl file; empty: the run's config.json "file"
};

struct AuditViolation {
  std::string where;          // "train step 812: moveArm(...)" (phase, step, task, the call)
  std::string first, second;  // the geoms
  double separation = 0;      // measured (negative: penetration depth)
  double required = 0;        // what the pair must keep
};

struct ClosestApproach {
  double distance = 0;  // metres (the cap when nothing came nearer)
  std::string where, first, second;
};

struct AuditReport {
  std::string run;
  std::int64_t motions = 0, segments = 0, states = 0;
  std::int64_t violationCount = 0;
  std::vector<AuditViolation> violations;          // the first AuditOptions::listed
  std::map<std::string, ClosestApproach> closest;  // per body class: each clearance, scenery, objects, self
  std::vector<std::string> classes;                // the classes in report order: the clearances as declared first
  // The record's completeness and its plans (app/audit/RecordContinuity.h): whether it marks plans and resets (so
  // that a motion not starting where the robot was left is a violation, a gap), the gaps, the plans it marks, those
  // a dry run accepted, and those of them the audit rejects (a violation or a gap in one of their motions).
  bool continuityChecked = false;
  std::int64_t gaps = 0, plans = 0, dryRunPlans = 0, dryRunPlansRejected = 0;
  std::string error;  // the run could not be audited (unreadable, no scene, ...)
  bool passed() const { return error.empty() && violationCount == 0; }
};

inline constexpr const char* kUnderAllow = " under an allow";  // suffix of the classes of excepted pairs

// Audits the run folder `runDir`. Never throws: problems land in `error`.
AuditReport auditRun(const std::string& runDir, const AuditOptions& options);

}  // namespace cbtl::app
