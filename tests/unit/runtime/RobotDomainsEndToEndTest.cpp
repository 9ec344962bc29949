// The robot domains end to end: each .cbtl file's tasks solved against its simulated scene (the world
// built-ins read the simulator's state, every plan is staged and dry-run) and executed by its simulator. Every
// task kind of every robot domain, on seeds 0-9: each request must be solved within the domain's budgets and
// its plan must execute without a failed action (competence, not just safety).
#include "tests/unit/runtime/TestPrograms.h"

#include "app/DomainSolverOptions.h"
#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "domains/books/BooksSimulator.h"
#include "domains/cleaning/CleaningSimulator.h"
#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "robot/world/MotionRecord.h"
#include "robot/world/RobotDistance.h"
#include "robot/world/Separation.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>

using namespace cbtl;

namespace {

// Under AddressSanitizer and UBSan (make asan: a Debug build, about 100x slower on these tests) the seed loops cover
// seeds 0-2 and the training regressions their first 60 steps: the same code paths for memory safety, in
// minutes instead of hours. The release build (make test) runs them in full.
#ifdef CBTL_SANITIZED_BUILD
constexpr bool kShortened = true;
#else
constexpr bool kShortened = false;
#endif
constexpr std::uint64_t kSeeds = kShortened ? 3 : 10;
constexpr std::int64_t kMaxTrainingSteps = kShortened ? 60 : std::numeric_limits<std::int64_t>::max();

struct RequestLog {
  std::string task;
  bool solved = false, dryRun = false, done = false, failed = false;
  std::string failure;   // the message of the step that failed the request
  sim::StepResult last;  // the step that ended the request
};

// One request: the task the world asks for, solved with the personalized constraints (an untrained user model,
// so they hold everywhere; with `fallback`, re-solved without them if they cannot hold) and executed call by call
// until its task ends or its calls are used up. `onStep` (when given) sees each call with its step.
using StepHook = std::function<void(const sim::ActionCall&, const sim::StepResult&)>;
RequestLog runRequest(app::LoadedProgram& lp, sim::DomainSimulator& world, solver::Solver& solver,
                      model::UserModel& user, bool fallback = true, const StepHook& onStep = {}) {
  RequestLog log;
  lp.syncWorld(world);
  const std::size_t task = lp.taskFor(world, 0);
  log.task = lp.graph().tasks[task].name;
  const auto obs = approach::observationVector(lp.program(), world.observe());
  approach::Plan plan = approach::makePlan(lp, task, obs, approach::evaluationChoice(), fallback, solver, user);
  log.solved = plan.ok;
  log.dryRun = plan.dryRun();
  for (const auto& call : plan.calls) {
    if (!plan.ok) break;
    sim::StepResult r = world.act(call);
    EXPECT_NE(r.status, sim::ActionStatus::UnknownAction) << call.name << ": " << r.message;
    if (r.status == sim::ActionStatus::Ignored && log.failure.empty()) log.failure = call.name + ": " + r.message;
    if (onStep) onStep(call, r);
    if (!r.feedback.empty()) {
      const auto report = lp.learner().learn(r.feedback, user, approach::StepWorld{plan.solve.assignment, obs});
      EXPECT_TRUE(report.problems.empty()) << report.problems.front();
    }
    if (r.taskDone) {
      log.done = true;
      log.failed = r.taskFailed;
      log.last = r;
      break;
    }
  }
  return log;
}

void expectCompetent(const RequestLog& r, std::uint64_t seed) {
  EXPECT_TRUE(r.solved) << r.task << " (seed " << seed << ") found no solution within the domain's budgets";
  EXPECT_TRUE(r.dryRun) << r.task << " (seed " << seed << ") was not dry-run";
  EXPECT_FALSE(r.failed) << r.task << " (seed " << seed << "): " << r.failure;
  EXPECT_TRUE(r.failure.empty()) << r.task << " (seed " << seed << "): " << r.failure;
}

std::unique_ptr<app::LoadedProgram> loadDomain(const std::string& name) {
  auto lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/" + name + "/" + name + ".cbtl");
  EXPECT_TRUE(lp->ok()) << lp->errors();
  return lp;
}

// What the home-scene robot holds at the start of a request.
enum class Holding { Nothing, Duster, Book };

// Arranges `w` (a freshly reset Cleaning or Books world) so that the robot holds `what`: a held object that is
// not wanted goes back where the scene keeps it (the duster on the main table, a book parked outside the room);
// a book to hold is one that is not on the furniture.
void arrangeHolding(world::World& w, Holding what, const std::map<std::string, world::Pose3>& scenePoses) {
  world::WorldState s = w.workspace().state();
  if (s.held) {
    const std::string held = s.held->object;
    s.held.reset();
    s.gripper = 1.0;
    s.objects[held] = held == "duster" ? scenePoses.at("duster") : s.objects.at(held);
    for (std::size_t k = 0; k < domains::home::kBookCount; ++k)
      if (domains::home::bookBody(k) == held) s.objects[held] = domains::home::parkedPose(k);
  }
  s.arm = domains::home::initialArm(w.workspace().scene());
  if (what == Holding::Duster) domains::home::holdCarried(s, "duster");
  if (what == Holding::Book) {
    // A parked book (one the user has); with every book on the furniture, the last of them.
    std::string book = domains::home::bookBody(domains::home::kBookCount - 1);
    for (std::size_t k = 0; k < domains::home::kBookCount; ++k) {
      const std::string body = domains::home::bookBody(k);
      if (domains::home::isParked(s.objects.at(body))) {
        book = body;
        break;
      }
    }
    domains::home::holdCarried(s, book);
  }
  ASSERT_EQ(w.workspace().setState(s), world::StateStatus::Ok);
}

std::map<std::string, world::Pose3> scenePoses(const app::LoadedProgram& lp) {
  world::Workspace ws(lp.scene());
  return ws.state().objects;
}

}  // namespace

TEST(RobotDomainsEndToEnd, CleaningEveryTaskOnSeedsZeroToNine) {
  auto lp = loadDomain("cleaning");
  const auto poses = scenePoses(*lp);
  const std::map<Holding, std::string> expected{
      {Holding::Nothing, "cleanSurface"}, {Holding::Duster, "cleanWithDusterInHand"}, {Holding::Book, "stowThenClean"}};
  for (const auto& [holding, task] : expected) {
    for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
      domains::cleaning::CleaningSimulator world(app::simulatorFacts(*lp), {}, seed);
      arrangeHolding(world.world(), holding, poses);
      ASSERT_EQ(world.requestedTask(), task);
      solver::Solver solver(app::domainSolverOptions("cleaning"), seed);
      model::UserModel user(lp->graph());
      const RequestLog r = runRequest(*lp, world, solver, user);
      expectCompetent(r, seed);
      EXPECT_TRUE(r.done) << task << " (seed " << seed << "): the wipe did not end the task";
    }
  }
}

// Held-out Cleaning worlds of the paper's protocol (evaluationTaskSeed of seeds 3, 9, 9, 4 and tasks 0, 4, 5, 6)
// whose obstacle book lies beside the duster's pole: the duster's first standard grasp has only colliding IK
// solutions there, so each request is solved only because the grasp is a CSP choice (fetchDuster.dusterGrasp).
TEST(RobotDomainsEndToEnd, CleaningWithABookBesideTheDusterChoosesAnotherGrasp) {
  auto lp = loadDomain("cleaning");
  for (std::uint64_t seed :
       {16941803161100891672ULL, 6140296996107935270ULL, 3997992992154806025ULL, 7421014871266783514ULL}) {
    domains::cleaning::CleaningSimulator world(app::simulatorFacts(*lp), {}, seed);
    solver::Solver solver(app::domainSolverOptions("cleaning"), seed);
    model::UserModel user(lp->graph());
    const RequestLog r = runRequest(*lp, world, solver, user);
    expectCompetent(r, seed);
    EXPECT_TRUE(r.done) << r.task << " (seed " << seed << "): the wipe did not end the task";
  }
}

TEST(RobotDomainsEndToEnd, BooksEveryTaskOnSeedsZeroToNine) {
  auto lp = loadDomain("books");
  const auto poses = scenePoses(*lp);
  for (Holding holding : {Holding::Nothing, Holding::Book}) {
    for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
      domains::books::BooksSimulator world(app::simulatorFacts(*lp), {}, seed);
      arrangeHolding(world.world(), holding, poses);
      ASSERT_EQ(world.requestedTask(), holding == Holding::Book ? "stowThenHandOverBook" : "handOverBook");
      solver::Solver solver(app::domainSolverOptions("books"), seed);
      model::UserModel user(lp->graph());
      const RequestLog r = runRequest(*lp, world, solver, user);
      expectCompetent(r, seed);
      EXPECT_TRUE(r.done) << r.task << " (seed " << seed << "): the handover did not end the task";
    }
  }
}

// Feeding's requests follow its cycle (two bites, the drink put in place, the drink offered); four requests from
// each seed's start cover every kind.
TEST(RobotDomainsEndToEnd, FeedingEveryTaskOnSeedsZeroToNine) {
  auto lp = loadDomain("feeding");
  std::map<std::string, int> kinds;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    auto world = domains::createSimulator("feeding", app::simulatorFacts(*lp), {}, seed);
    ASSERT_NE(world, nullptr);
    solver::Solver solver(app::domainSolverOptions("feeding"), seed);
    model::UserModel user(lp->graph());
    for (int request = 0; request < 4; ++request) {
      const RequestLog r = runRequest(*lp, *world, solver, user);
      expectCompetent(r, seed);
      EXPECT_TRUE(r.done) << r.task << " (seed " << seed << ")";
      ++kinds[r.task];
    }
  }
  EXPECT_GE(kinds["feedBite"], static_cast<int>(kSeeds));
  EXPECT_GE(kinds["prepareDrink"], static_cast<int>(kSeeds));
  EXPECT_GE(kinds["giveDrink"], static_cast<int>(kSeeds));
}

// Every served bite and drink reports the closest the robot came to the user (RobotDistance.h) and its slack to
// the separations feeding.cbtl declares, which IK, the planners, the dry run and the re-check all apply: the robot
// and what it holds stay 5 cm from the user's head and body (`clearance person`), the held utensil 5 mm from the
// head during the bite (its `allow`: the fork has to reach the mouth). No waypoint of any executed path comes closer.
TEST(RobotDomainsEndToEnd, FeedingReportsTheClearanceToTheUserOfEveryBite) {
  auto lp = loadDomain("feeding");
  int reported = 0;
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    auto world = domains::createSimulator("feeding", app::simulatorFacts(*lp), {}, seed);
    solver::Solver solver(app::domainSolverOptions("feeding"), seed);
    model::UserModel user(lp->graph());
    for (int request = 0; request < 4; ++request) {
      const RequestLog r = runRequest(*lp, *world, solver, user);
      expectCompetent(r, seed);
      if (r.task == "prepareDrink") continue;
      ASSERT_EQ(r.last.measures.size(), 2u) << r.task;
      EXPECT_EQ(r.last.measures[0].first, "userClearance");
      EXPECT_EQ(r.last.measures[1].first, "userKeepOutSlack");
      const double clearance = r.last.measures[0].second, slack = r.last.measures[1].second;
      EXPECT_GE(clearance, 0.005) << r.task << " seed " << seed << ": " << r.last.message;
      EXPECT_LT(clearance, 0.5) << r.task << " seed " << seed;
      EXPECT_GE(slack, 0.0) << r.task << " seed " << seed << ": " << r.last.message;
      EXPECT_LE(slack, clearance) << r.task << " seed " << seed;
      ++reported;
    }
  }
  EXPECT_GE(reported, static_cast<int>(kSeeds));
}

// A user who likes ketchup and nothing else, at meals without ketchup: the dip is drawn from what the table offers
// (dipChoices), so dipPreferred's relative scaling compares those and every bite is still served. Drawn from all
// five dips, no dip on such a table reached 0.95 of ketchup and the bite was unsatisfiable.
TEST(RobotDomainsEndToEnd, FeedingServesABiteWhenTheFavouriteSauceIsNotOnTheTable) {
  auto lp = loadDomain("feeding");
  int bitesWithoutTheFavourite = 0;
  for (std::uint64_t seed = 0; seed < 10; ++seed) {  // all ten even under the sanitizers: only some lack ketchup
    auto world = domains::createSimulator("feeding", app::simulatorFacts(*lp), {}, seed);
    ASSERT_NE(world, nullptr);
    const auto ketchupServed = [&] {
      const std::vector<std::string> onTable = world->observe().at("dipsOnTable").members;
      return std::find(onTable.begin(), onTable.end(), "ketchup") != onTable.end();
    };
    if (ketchupServed()) continue;
    solver::Solver solver(app::domainSolverOptions("feeding"), seed);
    model::UserModel user(lp->graph());
    // The answers are about this meal (its food and setting are the context they are learned in).
    lp->syncWorld(*world);
    const approach::StepWorld meal{{}, approach::observationVector(lp->program(), world->observe())};
    const sim::Value food = world->observe().at("foodOnPlate");
    for (const char* other : {"bbqSauce", "ranch", "hummus", "noDip"}) {
      const auto report = lp->learner().learn(
          {sim::FeedbackEvent{"dipAnswer", {food, sim::Value::name(other), sim::Value::name("ketchup")}}}, user, meal);
      ASSERT_TRUE(report.problems.empty()) << report.problems.front();
    }
    for (int request = 0; request < 4 && !ketchupServed(); ++request) {   // until the next meal
      const RequestLog r = runRequest(*lp, *world, solver, user, false);  // as CBTL's evaluation: no fallback
      expectCompetent(r, seed);
      if (r.task == "feedBite") ++bitesWithoutTheFavourite;
    }
  }
  EXPECT_GT(bitesWithoutTheFavourite, 0);
}

// An answer says one thing about each choice: the offered one is good iff it was the ideal, the ideal is good. When
// the robot offered the ideal, that is one label, not two (counted twice, a correct offer weighed double against a
// correction, so learners that exploit more learned from more weight per bite).
TEST(RobotDomainsEndToEnd, FeedingAnswersLabelEachChoiceOnce) {
  auto lp = loadDomain("feeding");
  auto world = domains::createSimulator("feeding", app::simulatorFacts(*lp), {}, 0);
  ASSERT_NE(world, nullptr);
  lp->syncWorld(*world);
  const approach::StepWorld meal{{}, approach::observationVector(lp->program(), world->observe())};
  const sim::Value food = world->observe().at("foodOnPlate");
  const auto labels = [&](sim::FeedbackEvent event) {
    model::UserModel user(lp->graph());
    const auto report = lp->learner().learn({std::move(event)}, user, meal);
    EXPECT_TRUE(report.problems.empty()) << report.problems.front();
    return report.labels;
  };
  const auto name = [](const char* n) { return sim::Value::name(n); };
  EXPECT_EQ(labels({"dipAnswer", {food, name("ketchup"), name("ketchup")}}), 1);
  EXPECT_EQ(labels({"dipAnswer", {food, name("ranch"), name("ketchup")}}), 2);
  EXPECT_EQ(labels({"signalAnswer", {name("button"), name("button")}}), 1);
  EXPECT_EQ(labels({"signalAnswer", {name("mouthOpen"), name("button")}}), 2);
  EXPECT_EQ(labels({"verbosityAnswer", {name("brief"), name("brief")}}), 1);
  EXPECT_EQ(labels({"verbosityAnswer", {name("chatty"), name("brief")}}), 2);
  EXPECT_EQ(labels({"verbosityNotWanted", {name("silent")}}), 1);
}

// Trains No Personalization on Books as `cbtl run domains/books/books.cbtl --approach no-personalization --seed
// SEED --steps STEPS --eval-every 500 --eval-tasks 2` does (the same training world).
approach::ExperimentResult trainBooksWithoutPersonalization(std::uint64_t seed, std::int64_t steps) {
  auto lp = loadDomain("books");
  approach::ExperimentConfig c;
  c.approach.kind = approach::ApproachKind::NoPersonalization;
  c.seed = seed;
  c.steps = std::min(steps, kMaxTrainingSteps);
  c.evalEvery = 500;
  c.evalTasks = 2;
  c.solverOptions = app::domainSolverOptions("books");
  const auto facts = app::simulatorFacts(*lp);
  const approach::SimulatorFactory factory = [&](const sim::SimulatorOptions& o, std::uint64_t s) {
    return domains::createSimulator("books", facts, o, s);
  };
  return approach::runExperiment(*lp, factory, c);
}

// `minRequests` is for the full run; a shortened one (sanitizers) must still have served at least one.
void expectNeverStuck(const approach::ExperimentResult& r, std::int64_t minRequests) {
  EXPECT_GE(r.train.requests, kShortened ? 1 : minRequests);
  EXPECT_EQ(r.train.solved, r.train.requests);
  EXPECT_EQ(r.train.failed, 0);
  EXPECT_EQ(r.train.caregiverResets, 0);
}

// Seed 5: on 2026-12-02 the robot had stowed Anne Frank 1.8 cm from the shelf's side support by step 221 and
// held another book the user could not reach; the only book left could not be grasped again (the joint segment
// into its grasp touched the support), so eight requests in a row exhausted every dry-run tier until a caregiver
// reset. moveTool now follows the tool's line (RobotActionsTest.MoveToolFollowsTheToolLineWhereTheJointSegmentTouches
// pins that case; this run need not meet it again once other changes alter the walk).
TEST(RobotDomainsEndToEnd, BooksTrainingWorldOfSeedFiveNeverGetsStuck) {
  expectNeverStuck(trainBooksWithoutPersonalization(5, 240), 15);
}

// Seed 0 up to step 1,490: the robot used to put books away on a side table at yaw 0, where their side grasp
// faces sideways from the table's approach base; with Pride and Prejudice stowed so and the only book left, five
// requests in a row found no reachable pre-grasp (steps 1,482-1,486) until a caregiver reset. Books are now put
// away at the yaw of the scene's own slots on each surface (books.cbtl, stowYaw).
TEST(RobotDomainsEndToEnd, BooksStowedOnASideTableCanBeFetchedAgain) {
  expectNeverStuck(trainBooksWithoutPersonalization(0, 1490), 100);
}

namespace {

// Puts `ws` at every state of a recorded arm motion, every `step` radians (L∞) of its joint path (continuous joints
// the short way round, as the record's segments go), and calls `visit` at each.
void forEachState(world::Workspace& ws, const world::ExecutedMotion& m, double step,
                  const std::function<void()>& visit) {
  ASSERT_EQ(ws.setState(m.start), world::StateStatus::Ok);
  const world::Scene& s = ws.scene();
  for (std::size_t i = 0; i + 1 < m.arm.size(); ++i) {
    world::ArmConfig delta{};
    double linf = 0;
    for (int j = 0; j < world::kArmDof; ++j) {
      delta[j] = s.armContinuous(j) ? world::angleDiff(m.arm[i + 1][j], m.arm[i][j]) : m.arm[i + 1][j] - m.arm[i][j];
      linf = std::max(linf, std::abs(delta[j]));
    }
    const int n = std::max(1, static_cast<int>(std::ceil(linf / step)));
    for (int k = i == 0 ? 0 : 1; k <= n; ++k) {
      world::ArmConfig q{};
      for (int j = 0; j < world::kArmDof; ++j) q[j] = m.arm[i][j] + delta[j] * k / n;
      ws.setArm(q);
      visit();
    }
  }
}

// The fork tip's path over a recorded motion, sampled every `step` radians.
struct ForkSample {
  Eigen::Vector3d tip;
  double toHead = 0;  // the fork's separation from the head (metres)
};
std::vector<ForkSample> forkAlong(world::Workspace& ws, const world::ExecutedMotion& m, double step) {
  const world::Scene& s = ws.scene();
  const int tip = s.siteId("utensil_tip"), fork = s.geomId("utensil_fork"), head = s.geomId("user_head_geom");
  std::vector<ForkSample> out;
  forEachState(ws, m, step, [&] {
    out.push_back({ws.sitePose(tip).position, world::exactSeparation(ws, fork, head)});
  });
  return out;
}

}  // namespace

// The bite reaches the mouth along a straight line in its last 10 cm (moveToolStraight inside the bite's `allow`):
// over the executed joint path, sampled every 1 mrad, the fork tip stays within 2 mm of the line from where the
// approach begins to the mouth (the tool follows its line to the IK's 1 mm / 0.01 rad, and the tip is 23 cm out), and
// its distance to the face never grows on the way in (within 0.1 mm). The worst deviation is printed for
// docs/domains-feeding.md.
TEST(RobotDomainsEndToEnd, FeedingBringsTheForkToTheMouthInAStraightLine) {
  auto lp = loadDomain("feeding");
  auto sim = domains::createSimulator("feeding", app::simulatorFacts(*lp), {}, 0);
  solver::Solver solver(app::domainSolverOptions("feeding"), 0);
  model::UserModel user(lp->graph());
  world::Workspace ws(lp->scene());
  double worstDeviation = 0, worstGrowth = 0, closest = 1;
  int approaches = 0;
  bool inward = true;  // the first straight move of a bite goes in, the second comes back out
  const StepHook measure = [&](const sim::ActionCall& call, const sim::StepResult& r) {
    // The bite's straight moves are the ones inside its `allow` (the drink's release backs off in a straight line
    // too, outside any).
    if (call.name != "moveToolStraight" || call.exceptions.empty()) return;
    inward = !inward;
    if (inward) return;  // this one came back out
    ASSERT_EQ(r.motions.size(), 1u);
    const auto samples = forkAlong(ws, world::motionFromJson(*lp->scene(), r.motions[0]), 0.001);
    const Eigen::Vector3d a = samples.front().tip, b = samples.back().tip, dir = (b - a).normalized();
    EXPECT_GT((b - a).norm(), 0.09);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const Eigen::Vector3d v = samples[k].tip - a;
      worstDeviation = std::max(worstDeviation, (v - v.dot(dir) * dir).norm());
      if (k > 0) worstGrowth = std::max(worstGrowth, samples[k].toHead - samples[k - 1].toHead);
      closest = std::min(closest, samples[k].toHead);
    }
    ++approaches;
  };
  for (int request = 0; request < 8 && approaches < 3; ++request)
    expectCompetent(runRequest(*lp, *sim, solver, user, true, measure), 0);
  ASSERT_GE(approaches, 3);
  std::printf(
      "bite approaches: %d; fork tip off the straight line at most %.3f mm; fork-face distance grows at most "
      "%.4f mm between samples on the way in; closest %.2f mm\n",
      approaches, worstDeviation * 1e3, worstGrowth * 1e3, closest * 1e3);
  EXPECT_LT(worstDeviation, 0.002);
  EXPECT_LT(worstGrowth, 0.0001);
  EXPECT_GE(closest, 0.005);  // the bite's exception: 5 mm from the face
}

// After a handover the Books robot backs away from the user before the arm folds: the move right after handOver()
// is a straight tool line (moveToolStraight) along which the robot's distance to the user never shrinks (sampled
// every 1 mrad of the executed joint path, within 0.1 mm), and no state of it is within the 5 cm clearance.
TEST(RobotDomainsEndToEnd, BooksBacksAwayFromTheUserAfterAHandover) {
  auto lp = loadDomain("books");
  auto sim = domains::createSimulator("books", app::simulatorFacts(*lp), {}, 1);
  solver::Solver solver(app::domainSolverOptions("books"), 1);
  model::UserModel user(lp->graph());
  world::Workspace ws(lp->scene());
  const std::vector<int> person{lp->scene()->bodyId("user")};
  int retreats = 0;
  double worstShrink = 0, closest = 1;
  std::string previous;
  const StepHook measure = [&](const sim::ActionCall& call, const sim::StepResult& r) {
    if (previous == "handOver") {
      EXPECT_EQ(call.name, "moveToolStraight");
      ASSERT_EQ(r.motions.size(), 1u);
      double last = -1;
      forEachState(ws, world::motionFromJson(*lp->scene(), r.motions[0]), 0.001, [&] {
        const double d = world::robotDistanceTo(ws, person, 0.5).distance;
        if (last >= 0) worstShrink = std::max(worstShrink, last - d);
        closest = std::min(closest, d);
        last = d;
      });
      ++retreats;
    }
    previous = call.name;
  };
  for (int request = 0; request < 6 && retreats < 3; ++request)
    expectCompetent(runRequest(*lp, *sim, solver, user, true, measure), 1);
  ASSERT_GE(retreats, 1);
  std::printf("Books retreats: %d; the distance to the user shrinks at most %.4f mm between samples; closest %.1f mm\n",
              retreats, worstShrink * 1e3, closest * 1e3);
  EXPECT_LT(worstShrink, 0.0001);
  EXPECT_GE(closest, 0.05);
}
