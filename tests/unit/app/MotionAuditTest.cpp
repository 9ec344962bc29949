// cbtl audit: a real run's motions pass; a forged motion into the table, a contact beyond its allowance and a
// motion that touches without one fail; what cannot be audited says why.
#include "app/audit/MotionAudit.h"

#include "app/DomainSolverOptions.h"
#include "app/LoadedProgram.h"
#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "robot/world/GraspClosure.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionRecord.h"
#include "robot/world/Scene.h"
#include "runtime/approach/Experiment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <string>

namespace cbtl::app {
namespace {

namespace fs = std::filesystem;

std::string domainFile(const std::string& d) { return std::string(CBTL_DOMAINS_DIR) + "/" + d + "/" + d + ".cbtl"; }

struct TempRun {
  fs::path dir;
  explicit TempRun(const std::string& name) : dir(fs::temp_directory_path() / ("cbtl_audit_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempRun() { fs::remove_all(dir); }
  void config(const std::string& program) const {
    std::ofstream(dir / "config.json") << "{\"file\": \"" << program << "\"}\n";
  }
  // `call`: the call each motion is recorded with (its "allow" is what the skill declared).
  void motions(const std::vector<std::string>& records,
               const std::string& call = R"({"name":"forged","args":[]})") const {
    std::ofstream out(dir / "motions.jsonl");
    for (const auto& r : records)
      out << R"({"phase":"train","step":1,"call":)" << call << R"(,"motion":)" << r << "}\n";
  }
  // Whole lines: motions (`motionLine`), plan and reset marks.
  void lines(const std::vector<std::string>& lines) const {
    std::ofstream out(dir / "motions.jsonl");
    for (const auto& l : lines) out << l << "\n";
  }
};

std::string motionLine(const std::string& motion) {
  return R"({"phase":"train","step":1,"call":{"name":"forged","args":[]},"motion":)" + motion + "}";
}

const std::shared_ptr<const world::Scene>& homeScene() {
  static const auto scene = world::Scene::loadFile(std::string(CBTL_DOMAINS_DIR) + "/home/home.xml").scene;
  return scene;
}

// The base drives 0.4 m along x in open floor, arm retracted: free.
world::ExecutedMotion freeBaseMotion() {
  world::ExecutedMotion m;
  m.kind = world::ExecutedMotion::Kind::Base;
  m.start.arm = world::configs::kRetract;
  m.start.base = {0.3, -0.4, 0};
  m.base = {{0.3, -0.4, 0}, {0.7, -0.4, 0}};
  return m;
}

TEST(MotionAudit, AFreeMotionPassesAndAMotionIntoTheTableFails) {
  TempRun run("forged");
  run.config(domainFile("cleaning"));
  const world::Scene& scene = *homeScene();
  world::ExecutedMotion into = freeBaseMotion();
  // From beside the main table (x -0.75 +- 0.1, top at z 0) straight through it: the stand is 0.39 m tall.
  into.start.base = {-0.3, 0.0, 0};
  into.base = {{-0.3, 0.0, 0}, {-0.75, 0.0, 0}};
  run.motions({world::motionToJson(scene, freeBaseMotion())});
  AuditReport ok = auditRun(run.dir.string(), {});
  EXPECT_TRUE(ok.passed()) << ok.error << " " << ok.violationCount;
  EXPECT_EQ(ok.motions, 1);
  EXPECT_GT(ok.states, 100);  // 0.4 m at 2 mm

  run.motions({world::motionToJson(scene, freeBaseMotion()), world::motionToJson(scene, into)});
  AuditOptions all;
  all.listed = 100000;
  const AuditReport bad = auditRun(run.dir.string(), all);
  EXPECT_FALSE(bad.passed());
  ASSERT_GT(bad.violationCount, 0);
  // First it comes within cleaning.cbtl's 1 cm furniture clearance, then it drives into the table.
  EXPECT_EQ(bad.violations.front().second, "table_top") << bad.violations.front().first;
  EXPECT_NEAR(bad.violations.front().required, 0.01, 1e-12);
  EXPECT_LT(bad.violations.front().separation, 0.01);
  EXPECT_EQ(static_cast<std::int64_t>(bad.violations.size()), bad.violationCount);
  double deepest = 0;
  for (const AuditViolation& v : bad.violations) deepest = std::min(deepest, v.separation);
  EXPECT_LT(deepest, 0.0) << "it ends inside the table";
}

// The record marks plans and resets: a motion that does not start where the last one left the robot is a gap (the
// robot moved in a way nobody audited), and a plan a dry run accepted with such a motion, or with a contact, is
// counted as rejected. Between a reset and the next motion the robot may be anywhere. An unmarked record (written
// before the marks) is not checked for gaps.
TEST(MotionAudit, ARobotThatMovedWithoutARecordedMotionFails) {
  TempRun run("gap");
  run.config(domainFile("cleaning"));
  const world::Scene& scene = *homeScene();
  const std::string plan = R"({"phase":"train","step":1,"plan":{"calls":["moveBase"],"dry_run":true}})";
  const std::string reset = R"({"phase":"train","step":1,"reset":"caregiver"})";
  world::ExecutedMotion first = freeBaseMotion(), again = freeBaseMotion();  // again: from (0.3, -0.4), not (0.7, -0.4)
  const std::string a = motionLine(world::motionToJson(scene, first)),
                    b = motionLine(world::motionToJson(scene, again));

  run.lines({plan, a, plan, b});
  const AuditReport gap = auditRun(run.dir.string(), {});
  EXPECT_TRUE(gap.continuityChecked);
  EXPECT_FALSE(gap.passed());
  EXPECT_EQ(gap.gaps, 1);
  ASSERT_EQ(gap.violationCount, 1);
  EXPECT_NEAR(gap.violations.front().separation, 0.4, 1e-9) << gap.violations.front().where;
  EXPECT_EQ(gap.plans, 2);
  EXPECT_EQ(gap.dryRunPlans, 2);
  EXPECT_EQ(gap.dryRunPlansRejected, 1);

  run.lines({plan, a, reset, plan, b});
  const AuditReport afterReset = auditRun(run.dir.string(), {});
  EXPECT_TRUE(afterReset.passed()) << afterReset.violationCount;
  EXPECT_EQ(afterReset.gaps, 0);

  // Continuing from where the first left the robot: no gap.
  world::ExecutedMotion on = freeBaseMotion();
  on.start.base = {0.7, -0.4, 0};
  on.base = {{0.7, -0.4, 0}, {0.7, -0.1, 0}};
  run.lines({plan, a, motionLine(world::motionToJson(scene, on))});
  const AuditReport continued = auditRun(run.dir.string(), {});
  EXPECT_TRUE(continued.passed()) << continued.violationCount;
  EXPECT_EQ(continued.dryRunPlansRejected, 0);

  // A plan the dry run accepted whose motion drives into the table: rejected here.
  world::ExecutedMotion into = freeBaseMotion();
  into.start.base = {-0.3, 0.0, 0};
  into.base = {{-0.3, 0.0, 0}, {-0.75, 0.0, 0}};
  run.lines({reset, plan, motionLine(world::motionToJson(scene, into))});
  const AuditReport contact = auditRun(run.dir.string(), {});
  EXPECT_FALSE(contact.passed());
  EXPECT_EQ(contact.gaps, 0);
  EXPECT_EQ(contact.dryRunPlansRejected, 1);

  run.lines({a, b});
  const AuditReport unmarked = auditRun(run.dir.string(), {});
  EXPECT_FALSE(unmarked.continuityChecked);
  EXPECT_TRUE(unmarked.passed());
}

// The robot holding `book` between its fingers (the book's centre 7 cm past the tool frame, its thickness across
// them), the gripper closed on it as a grasp closes: base at `base`, the tool at `tool` (an IK solution from kHome;
// `tool` should point along +y with its x along world x).
// nullopt when IK fails.
std::optional<world::WorldState> holdingBook(const std::string& book, const world::Pose2& base,
                                             const world::Pose3& tool) {
  world::Workspace ws(homeScene());
  world::WorldState st;
  st.arm = world::configs::kHome;
  st.base = base;
  if (ws.setState(st) != world::StateStatus::Ok) return std::nullopt;
  world::Rng rng(3);
  world::IkOptions ik;
  ik.requireCollisionFree = false;
  ik.positionTolerance = 1e-6;  // the tests press the book in by fractions of a millimetre
  ik.rotationTolerance = 1e-5;
  ik.maxIterations = 1000;
  const world::IkResult r = world::solveIk(ws, tool, world::configs::kHome, rng, ik);
  if (!r.solved()) return std::nullopt;
  st.arm = r.q;
  // Upright in the gripper reaching along +y: the book's z along the tool's -y (world up), its thickness (x) across
  // the fingers, its 10 cm depth along the approach.
  st.held =
      world::Grasp{book, {{0, 0, 0.07}, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()))}};
  for (int k = 0; k < 9; ++k)  // every other book far outside the room
    if ("book_" + std::to_string(k) != book)
      st.objects["book_" + std::to_string(k)] = world::Pose3::fromPosition({20.0 + k, 20, 0});
  if (ws.setState(st) != world::StateStatus::Ok || !world::gripHeld(ws).holds()) return std::nullopt;
  return ws.state();
}

// A held book pushed 0.5 mm into the shelf it stands on: a contact unless the motion's record allows it, and then
// only up to the allowed depth.
TEST(MotionAudit, AContactPassesOnlyWithinTheAllowanceItsRecordDeclares) {
  TempRun run("allowance");
  run.config(domainFile("books"));
  const world::Scene& scene = *homeScene();
  const int shelf = scene.geomId("shelf_layer_1");
  // shelf_layer_1: centre (0, 0.75, 0), half-height 0.05, top at z 0.05; a book's half-height is 0.08. The gripper
  // reaches into the shelf along +y from the base at the origin, its fingers closing along world x.
  const Eigen::Quaterniond intoShelf(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  auto atDepth = [&](double depth, double allowed) {
    const world::Pose3 tool{{0.0, 0.75 - 0.07, 0.05 + 0.08 - depth}, intoShelf};
    const auto start = holdingBook("book_4", {0, 0, 0}, tool);
    EXPECT_TRUE(start.has_value());
    world::ExecutedMotion h;
    h.kind = world::ExecutedMotion::Kind::Base;
    h.start = start.value_or(world::WorldState{});
    // The base moves 1 mm along x (a zero-length motion would be dropped): the book slides on the shelf.
    h.base = {h.start.base, {h.start.base.x + 0.001, h.start.base.y, 0}};
    if (allowed > 0) {
      world::ContactAllowance a;
      a.geom = shelf;
      a.separation = -allowed;
      h.allowances.push_back(a);
    }
    return world::motionToJson(scene, h);
  };
  run.motions({atDepth(0.0005, 0.001)});
  const AuditReport allowed = auditRun(run.dir.string(), {});
  EXPECT_TRUE(allowed.passed()) << allowed.error << " " << allowed.violationCount
                                << (allowed.violations.empty() ? "" : " " + allowed.violations.front().second);
  run.motions({atDepth(0.0005, 0.0)});
  EXPECT_FALSE(auditRun(run.dir.string(), {}).passed());
  run.motions({atDepth(0.002, 0.001)});
  const AuditReport deep = auditRun(run.dir.string(), {});
  ASSERT_FALSE(deep.passed());
  EXPECT_EQ(deep.violations.front().second, "shelf_layer_1");
  EXPECT_NEAR(deep.violations.front().separation, -0.002, 1e-4);

  // Deeper than a resting contact: the record's allowance must be one the call's `allow` declared.
  run.motions({atDepth(0.003, 0.004)});
  const AuditReport forged = auditRun(run.dir.string(), {});
  ASSERT_FALSE(forged.passed());
  EXPECT_NE(forged.violations.front().where.find("no `allow` of the call declares"), std::string::npos)
      << forged.violations.front().where;
  run.motions({atDepth(0.003, 0.004)},
              R"({"name":"place","args":[],"allow":[{"part":"held","names":["shelf_layer_1"],"separation":-0.004,)"
              R"("declared_at":"books.cbtl:1:1"}]})");
  const AuditReport declared = auditRun(run.dir.string(), {});
  EXPECT_TRUE(declared.passed()) << declared.error << " " << declared.violationCount
                                 << (declared.violations.empty() ? "" : " " + declared.violations.front().where);
}

// The grip is audited too: a held book the fingers close into (the gripper fully closed on a 4 cm book) or that no
// finger touches (held in the air) fails, as a grip closed to the book's width passes.
TEST(MotionAudit, AGripMustTouchWhatItHoldsWithoutPressingIntoIt) {
  TempRun run("grip");
  run.config(domainFile("books"));
  const world::Scene& scene = *homeScene();
  const Eigen::Quaterniond intoShelf(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  const auto start = holdingBook("book_4", {0, 0, 0}, {{0.0, 0.68, 0.2}, intoShelf});  // between two shelf layers
  ASSERT_TRUE(start.has_value());
  auto record = [&](const world::WorldState& s) {
    world::ExecutedMotion m;
    m.kind = world::ExecutedMotion::Kind::Base;
    m.start = s;
    m.base = {s.base, {s.base.x - 0.01, s.base.y, 0}};
    return world::motionToJson(scene, m);
  };
  run.motions({record(*start)});
  const AuditReport gripped = auditRun(run.dir.string(), {});
  EXPECT_TRUE(gripped.passed()) << gripped.error << " " << gripped.violationCount
                                << (gripped.violations.empty() ? "" : " " + gripped.violations.front().where);
  ASSERT_EQ(gripped.closest.count("grip"), 1u);
  EXPECT_NEAR(gripped.closest.at("grip").distance, -world::kGraspSqueeze, 2e-4);

  world::WorldState crushed = *start;
  crushed.gripper = 0.0;
  run.motions({record(crushed)});
  const AuditReport tooDeep = auditRun(run.dir.string(), {});
  ASSERT_FALSE(tooDeep.passed());
  EXPECT_NE(tooDeep.violations.front().where.find("beyond the pads' compliance"), std::string::npos)
      << tooDeep.violations.front().where;
  EXPECT_LT(tooDeep.violations.front().separation, -0.015);

  world::WorldState floating = *start;
  floating.held->toolToObject = world::Pose3::fromPosition({0, 0, 0.30});
  run.motions({record(floating)});
  const AuditReport air = auditRun(run.dir.string(), {});
  ASSERT_FALSE(air.passed());
  EXPECT_NE(air.violations.front().where.find("does not touch"), std::string::npos) << air.violations.front().where;
}

TEST(MotionAudit, SaysWhyARunCannotBeAudited) {
  TempRun run("unreadable");
  EXPECT_NE(auditRun(run.dir.string(), {}).error.find("config.json"), std::string::npos);
  run.config(domainFile("cleaning"));
  EXPECT_NE(auditRun(run.dir.string(), {}).error.find("motions.jsonl"), std::string::npos);
  std::ofstream(run.dir / "motions.jsonl") << "{\"phase\":\"train\",\"motion\":{\"kind\":\"sideways\"}}\n";
  const AuditReport r = auditRun(run.dir.string(), {});
  EXPECT_NE(r.error.find("motions.jsonl:1"), std::string::npos) << r.error;
  EXPECT_FALSE(r.passed());
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A CBTL run of `domain` into `dir`: `steps` training steps, an evaluation (one task) every `evalEvery`.
// `program`: the domain's .cbtl file by default.
approach::ExperimentResult runDomain(const std::string& domain, const std::string& dir, approach::RunMode mode,
                                     std::int64_t steps, std::int64_t evalEvery,
                                     std::function<void(const char*, std::int64_t)> hook = {},
                                     const std::string& program = "") {
  const auto lp = LoadedProgram::load(program.empty() ? domainFile(domain) : program);
  EXPECT_TRUE(lp->ok()) << domain << ": " << lp->errors();
  const auto facts = std::make_shared<domains::ProgramFacts>(simulatorFacts(*lp));
  approach::ExperimentConfig c;
  c.approach.kind = approach::ApproachKind::Cbtl;
  c.steps = steps;
  c.evalEvery = evalEvery;
  c.evalTasks = 1;
  c.solverOptions = domainSolverOptions(domain);
  c.outDir = dir;
  c.runMode = mode;
  c.testHook = std::move(hook);
  return approach::runExperiment(
      *lp,
      [facts, domain](const sim::SimulatorOptions& o, std::uint64_t seed) {
        return domains::createSimulator(domain, *facts, o, seed);
      },
      c);
}

// Interrupted between checkpoints and resumed, a robot run's record holds the same bytes as an uninterrupted one's.
TEST(MotionAudit, AResumedRunRecordsTheSameMotions) {
  struct Interrupted {};
  TempRun whole("resume_whole"), cut("resume_cut");
  runDomain("cleaning", whole.dir.string(), approach::RunMode::Force, 60, 20);
  EXPECT_THROW(runDomain("cleaning", cut.dir.string(), approach::RunMode::Force, 60, 20,
                         [](const char* point, std::int64_t step) {
                           if (step == 37 && std::string(point) == "step") throw Interrupted{};
                         }),
               Interrupted);
  runDomain("cleaning", cut.dir.string(), approach::RunMode::Resume, 60, 20);
  const std::string a = readAll(whole.dir / "motions.jsonl.gz"), b = readAll(cut.dir / "motions.jsonl.gz");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
}

// A real run of each robot domain records its motions and they pass the audit.
TEST(MotionAudit, RealRunsOfEveryRobotDomainPass) {
  for (const std::string domain : {"cleaning", "books", "feeding"}) {
    TempRun run("real_" + domain);
    runDomain(domain, run.dir.string(), approach::RunMode::Force, 40, 40);
    // The run's config names the program as given; point the audit at it explicitly as well.
    AuditOptions o;
    o.program = domainFile(domain);
    const AuditReport r = auditRun(run.dir.string(), o);
    EXPECT_TRUE(r.passed()) << domain << ": " << r.error << " " << r.violationCount
                            << (r.violations.empty() ? "" : " " + r.violations.front().where);
    EXPECT_GT(r.motions, 5) << domain;
    // The record is whole (every motion starts where the robot was left), and every plan was dry-run.
    EXPECT_TRUE(r.continuityChecked) << domain;
    EXPECT_EQ(r.gaps, 0) << domain;
    EXPECT_GT(r.plans, 0) << domain;
    EXPECT_EQ(r.dryRunPlans, r.plans) << domain;
    EXPECT_EQ(r.dryRunPlansRejected, 0) << domain;
    // Pairs skipped while a distance bound shows they cannot matter change nothing: measured at every state, the
    // report is the same.
    o.skipFarPairs = false;
    const AuditReport every = auditRun(run.dir.string(), o);
    EXPECT_EQ(every.states, r.states) << domain;
    EXPECT_EQ(every.violationCount, r.violationCount) << domain;
    ASSERT_EQ(every.closest.size(), r.closest.size()) << domain;
    for (const auto& [cls, c] : every.closest) {
      ASSERT_EQ(r.closest.count(cls), 1u) << domain << " " << cls;
      EXPECT_NEAR(r.closest.at(cls).distance, c.distance, 1e-9) << domain << " " << cls;
    }
  }
}

// Writes a copy of `domain`'s program into `dir` whose world is its scene with `extra` (MJCF) added to the
// worldbody; returns the program's path.
std::string changedWorld(const std::string& domain, const fs::path& dir, const std::string& extra) {
  const std::string sceneName = domain == "feeding" ? "feeding/feeding.xml" : "home/home.xml";
  std::string scene = readAll(fs::path(CBTL_DOMAINS_DIR) / sceneName);
  scene.replace(scene.find("</worldbody>"), 0, extra + "\n");
  // Beside a copy of the arm's file, where the scene's include (../assets/gen3.xml) finds it.
  fs::create_directories(dir / "scene");
  fs::create_directories(dir / "assets");
  fs::copy_file(fs::path(CBTL_DOMAINS_DIR) / "assets" / "gen3.xml", dir / "assets" / "gen3.xml");
  std::ofstream(dir / "scene" / "changed.xml") << scene;
  std::string program = readAll(domainFile(domain));
  const std::size_t at = program.find("world \"");
  program.replace(at, program.find(';', at) - at, "world \"scene/changed.xml\"");
  const fs::path path = dir / (domain + ".cbtl");
  std::ofstream(path) << program;
  return path.string();
}

// The world changes and every executed plan is still certified: a chair in the home scene's room (beside the bed,
// where the robot drives to hand over a book: the old checks let it touch the user there), a box on Feeding's
// table. The runs adapt to the new scene (it is the program's world) and their records pass the audit.
TEST(MotionAudit, RunsInAChangedWorldPassTheAudit) {
  const std::string chair =
      R"(<body name="chair" pos="1.3 -0.45 0"><geom name="chair_seat" type="box" pos="0 0 0.45" size="0.22 0.22 0.03"/>)"
      R"(<geom name="chair_back" type="box" pos="0.2 0 0.75" size="0.02 0.22 0.3"/></body>)";
  const std::string box =
      R"(<body name="box" pos="0.16 0.78 0.19"><geom name="box_geom" type="box" size="0.03 0.03 0.04"/></body>)";
  for (const std::string domain : {"cleaning", "books", "feeding"}) {
    TempRun run("changed_" + domain);
    const std::string program = changedWorld(domain, run.dir, domain == "feeding" ? box : chair);
    const fs::path out = run.dir / "run";
    runDomain(domain, out.string(), approach::RunMode::Force, 40, 40, {}, program);
    AuditOptions o;
    o.program = program;
    const AuditReport r = auditRun(out.string(), o);
    EXPECT_TRUE(r.passed()) << domain << ": " << r.error << " " << r.violationCount
                            << (r.violations.empty() ? "" : " " + r.violations.front().where);
    EXPECT_GT(r.motions, 5) << domain;
    const std::string added = domain == "feeding" ? "box_geom" : "chair_seat";
    EXPECT_NE(readAll(run.dir / "scene" / "changed.xml").find(added), std::string::npos);
  }
}

}  // namespace
}  // namespace cbtl::app
