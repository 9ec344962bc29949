// The language's built-ins end to end: std.geometry's poses, text concatenation, observed-set domains and
// observation-initialized domains, and the robot world bound through robot/bind (kinematics, IK samplers,
// collision, occlusion, placement, motion-plan feasibility, scene queries) on the Feeding and home scenes.
#include "tests/unit/runtime/TestPrograms.h"

#include "robot/actions/StandardGrasps.h"
#include "robot/bind/WorldBuiltins.h"
#include "robot/world/WorldState.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/Solver.h"

#include <gtest/gtest.h>

#include <set>

#include <cmath>

using namespace cbtl;

namespace {

const std::string kDomains = CBTL_DOMAINS_DIR;

// Evaluates every hard constraint of the program's first task on its initial assignment.
std::vector<std::pair<std::string, bool>> checkAll(app::LoadedProgram& lp, const std::vector<double>& obs = {}) {
  const auto& program = lp.program();
  std::vector<double> o = obs;
  o.resize(program.observationWidth() + 1, 0.0);
  std::vector<double> x = program.initialAssignment(o);
  std::vector<double> frame(64);
  rt::EvalContext ctx{x.data(), o.data(), frame.data(), program.callContext()};
  std::vector<std::pair<std::string, bool>> out;
  for (std::size_t c = 0; c < program.constraints().size(); ++c) {
    out.emplace_back(program.constraints()[c].source->name,
                     program.pool().evalBool(program.constraints()[c].root, ctx));
  }
  return out;
}

void expectAllHold(app::LoadedProgram& lp, const std::vector<double>& obs = {}) {
  for (const auto& [name, ok] : checkAll(lp, obs)) EXPECT_TRUE(ok) << name;
}

solver::SolveResult solveHard(app::LoadedProgram& lp, std::size_t task, const std::vector<double>& obs,
                              std::uint64_t seed = 1) {
  model::UserModel user(lp.graph());
  std::vector<double> o = obs;
  o.resize(lp.program().observationWidth(), 0.0);
  const solver::Csp csp = solver::makeCsp(lp.program(), static_cast<std::uint32_t>(task), lp.instances(task), user, o,
                                          solver::PersonalMode::Exclude, solver::CostKind::None);
  solver::SolverOptions options;
  options.maxIters = 5000;
  solver::Solver s(options, seed);
  return s.solve(csp);
}

std::string feedingPrelude() {
  return "domain w;\nimport std.geometry;\nimport std.kinova;\nimport std.collision;\nimport std.occlusion;\nworld \"" +
         kDomains + "/feeding/feeding.xml\";\n";
}
std::string homePrelude() {
  return "domain h;\nimport std.geometry;\nimport std.kinova;\nimport std.collision;\nworld \"" + kDomains +
         "/home/home.xml\";\n";
}

}  // namespace

TEST(PoseBuiltins, ComposeInverseRetargetAndToolDown) {
  auto lp = test::compileOrFail("p.cbtl", R"(domain p;
import std.geometry;
const a = poseRpy(vec3(0.1, -0.2, 0.3), 0.3, -0.2, 1.0);
const b = poseQuat(vec3(-0.5, 0.4, 0.0), 0.1, 0.2, 0.3, 0.9);
require inverseUndoes: distance(transformPoint(compose(a, inverse(a)), vec3(1, 2, 3)), vec3(1, 2, 3)) < 1e-9;
require relativeIsComposeOfInverse: angleBetween(relativePose(a, b), compose(inverse(a), b)) < 1e-9
    and distance(relativePose(a, b).position, compose(inverse(a), b).position) < 1e-9;
require relativeThenCompose: distance(compose(a, relativePose(a, b)).position, b.position) < 1e-9
    and angleBetween(compose(a, relativePose(a, b)), b) < 1e-6;
require retargetToSameIsIdentity: angleBetween(retarget(b, a, a), b) < 1e-6 and distance(retarget(b, a, a).position, b.position) < 1e-9;
require retargetFollowsTheObject: distance(retarget(poseAt(vec3(1, 0, 0)), poseAt(vec3(0, 0, 0)), poseAt(vec3(0, 2, 0))).position, vec3(1, 2, 0)) < 1e-9;
require toolDownPointsDown: abs(transformPoint(toolDownAbove(vec3(1, 2, 0), 0.5, 0.7), vec3(0, 0, 1)).z - (-0.5)) < 1e-9;
require poseAboveRaises: abs(poseAbove(b, 0.25).z - 0.25) < 1e-12 and angleBetween(poseAbove(b, 0.25), b) < 1e-9;
require rpyYaw: angleBetween(poseRpy(vec3(0, 0, 0), 0, 0, 0.5), poseRpy(vec3(0, 0, 0), 0, 0, -0.5)) > 0.999 and
    angleBetween(poseRpy(vec3(0, 0, 0), 0, 0, 0.5), poseRpy(vec3(0, 0, 0), 0, 0, -0.5)) < 1.001;
require se2RoundTrip: se2Distance(compose2(se2(1, 2, 0.5), relative2(se2(1, 2, 0.5), se2(-1, 0.3, -2.0))), se2(-1, 0.3, -2.0)) < 1e-9;
require se2DistanceCountsYaw: abs(se2Distance(se2(0, 0, 0), se2(3, 4, 0.5)) - 5.5) < 1e-12;
require liftToSe3: abs(se2AtHeight(se2(1, 2, 0.3), 0.7).z - 0.7) < 1e-12;
)");
  ASSERT_TRUE(lp->ok());
  expectAllHold(*lp);
}

TEST(PoseBuiltins, SamplersStayInTheirSets) {
  auto lp = test::compileOrFail("s.cbtl", R"(domain s;
import std.geometry;
var p : vec<3>;
var b : SE2;
var t : SE3;
require inShell: distance(p, vec3(1, 1, 1)) >= 0.2 - 1e-9 and distance(p, vec3(1, 1, 1)) <= 0.5 + 1e-9;
require near: abs(b.x - 1) <= 0.1 and abs(b.y + 1) <= 0.1 and b.yaw == 0.5;
require down: abs(transformPoint(t, vec3(0, 0, 1)).z - (t.z - 1)) < 1e-9 and abs(t.z - 0.3) < 1e-12;
sample p ~ pointInShell(vec3(1, 1, 1), 0.2, 0.5);
sample b ~ se2Near(se2(1, -1, 0.5), 0.1);
sample t ~ toolDownAboveSampler(vec3(0, 0, 0.1), 0.2, pi);
)");
  ASSERT_TRUE(lp->ok());
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto r = solveHard(*lp, 0, {}, seed);
    EXPECT_EQ(r.outcome, solver::SolveOutcome::Solved) << seed;
  }
}

TEST(TextBuiltins, ConcatenationInternsTheJoinedText) {
  auto lp = test::compileOrFail("t.cbtl", R"(domain t;
observe food : text;
require joined: "bite of " + food + "." == "bite of fries.";
)");
  ASSERT_TRUE(lp->ok());
  const double fries = lp->program().strings().intern("fries");
  EXPECT_TRUE(checkAll(*lp, {fries}).at(0).second);
  const double soup = lp->program().strings().intern("soup");
  EXPECT_FALSE(checkAll(*lp, {soup}).at(0).second);
}

TEST(ObservedDomains, ASetObservationRestrictsTheVariable) {
  auto lp = test::compileOrFail("o.cbtl", R"(domain o;
enum E { a, b, c, d }
observe allowed : set<E>;
var e : E;
var f : E in allowed;
sample e ~ uniform;
sample f ~ uniform;
require differ: e != f;
)");
  ASSERT_TRUE(lp->ok());
  ASSERT_EQ(lp->program().observationWidth(), 4u);  // one membership flag per member
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const auto r = solveHard(*lp, 0, {0, 0, 1, 0}, seed);  // only c
    ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
    EXPECT_EQ(r.assignment[1], 2.0);  // f = c
  }
  EXPECT_EQ(solveHard(*lp, 0, {0, 0, 0, 0}).outcome, solver::SolveOutcome::InfeasibleWithinBudget);
}

TEST(ObservedDomains, UniformDrawsComeOnlyFromTheObservedMembers) {
  // A uniform sampler of a variable whose domain is an observed set draws among the listed members only, so the
  // domain constraint never rejects a draw: no iteration is spent on a member the world does not offer.
  auto lp = test::compileOrFail("u.cbtl", R"(domain u;
enum E { a, b, c, d, e, f, g, h }
observe offered : set<E>;
var x : E in offered;
var y : real in 0 .. 1 = 0;
sample x ~ uniform;
sample y ~ uniform;
require moved: y > 0.9;
)");
  ASSERT_TRUE(lp->ok());
  std::set<double> drawn;
  std::uint64_t domainEvaluations = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    // Only a (x's initial value, so the first candidate is in the domain) and g.
    const auto r = solveHard(*lp, 0, {1, 0, 0, 0, 0, 0, 1, 0}, seed);
    ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
    drawn.insert(r.assignment[0]);
    for (const auto& c : r.constraints) {
      if (c.ref.kind != solver::ConstraintKind::Hard || lp->graph().constraints[c.ref.index].name != "x.domain")
        continue;
      domainEvaluations += c.evaluations;
      EXPECT_EQ(c.rejections, 0u) << "seed " << seed;
    }
  }
  EXPECT_GT(domainEvaluations, 40u);
  EXPECT_EQ(drawn, (std::set<double>{0.0, 6.0}));
}

TEST(ObservedDomains, AnInitialValueFromAnObservationMustLieInTheDomain) {
  auto lp = test::compileOrFail("i.cbtl", R"(domain i;
observe here : vec<2>;
var p : vec<2> in [0.3 .. 0.4, 0.2 .. 0.6] = here;
sample p ~ uniform;
)");
  ASSERT_TRUE(lp->ok());
  const auto r = solveHard(*lp, 0, {0.0, 0.0});
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  EXPECT_GE(r.assignment[0], 0.3);
  EXPECT_LE(r.assignment[0], 0.4);
  const auto kept = solveHard(*lp, 0, {0.35, 0.5});
  ASSERT_EQ(kept.outcome, solver::SolveOutcome::Solved);
  EXPECT_EQ(kept.assignment[0], 0.35);  // inside the domain, the initial value is the first candidate
}

TEST(WorldBuiltins, KinematicsCollisionAndOcclusionOnTheFeedingScene) {
  auto lp = test::compileOrFail("w.cbtl", feedingPrelude() + R"(
const retract = namedConf("retract");
const front = poseQuat(vec3(-0.05, 0.5, 0.77), 0, -0.7071068, 0, 0.7071068);
require fkRetract: distance(toolPose(retract).position, vec3(0.1305, 0.0014, 0.2087)) <= 0.001;
require fkZero: distance(toolPose(namedConf("zero")).position, vec3(0, -0.0249, 1.3074)) <= 0.001;
require retractIsFree: confCollisionFree(retract) and withinJointLimits(retract);
require throughTable: not confCollisionFree(gen3Conf(-0.828, 0.843, 2.992, -1.341, 0.135, -0.966, -1.004));
require foldedIntoItself: not confCollisionFree(gen3Conf(0, 0, 0, 2.6, 0, 2.2, 0));
require retractDoesNotOcclude: occlusion(retract) == 0;
require unknownNameIsNoConfiguration: not withinJointLimits(namedConf("noSuchPose"));
require jointDistanceWraps: abs(jointDistance(gen3Conf(3.1, 0, 0, 0, 0, 0, 0), gen3Conf(-3.1, 0, 0, 0, 0, 0, 0)) - (2 * pi - 6.2)) < 1e-9;
require plateAndDrinkOverlap: not bodiesApartAtXY("plate", vec2(0.34, 0.4), "drink", vec2(0.34, 0.4));
require plateAndDrinkApart: bodiesApartAtXY("plate", vec2(0.34, 0.3), "drink", vec2(0.34, 0.7));
require plateStandsOnTheTable: supportedAtXY("plate", vec2(0.34, 0.3));
require plateOffTheTableDoesNot: not supportedAtXY("plate", vec2(0.34, 1.2));
require unknownBodyStandsNowhere: not supportedAtXY("teapot", vec2(0.34, 0.3));
require plateIsWhereTheSceneSays: distance(bodyPose("plate").position, vec3(0.30, 0.25, 0.1625)) < 1e-6;
require eyesSite: distance(sitePose("user_eyes").position, vec3(-0.3, 0.5, 0.77)) < 1e-6;
require frontIsReachable: ikExists(front);
require farIsNot: not ikExists(poseAt(vec3(3, 0, 0.5)));
require retractToBeforeTransfer: motionPlanExists(retract, namedConf("beforeTransfer"));
)");
  ASSERT_TRUE(lp->ok());
  expectAllHold(*lp);
}

TEST(WorldBuiltins, IkSamplerReachesAndTheArmInFrontOfTheEyesOccludes) {
  auto lp = test::compileOrFail("k.cbtl", feedingPrelude() + R"(
const front = poseQuat(vec3(-0.05, 0.5, 0.77), 0, -0.7071068, 0, 0.7071068);
var q : Conf<gen3>;
require reachesFront: reaches(q, front);
require free: confCollisionFree(q);
require blocksTheView: occlusion(q) >= 0.05;
sample q ~ ikSample(front);
)");
  ASSERT_TRUE(lp->ok());
  const auto r = solveHard(*lp, 0, {});
  EXPECT_EQ(r.outcome, solver::SolveOutcome::Solved);
}

TEST(WorldBuiltins, FeedingTasksSolveAgainstTheScene) {
  auto lp = app::LoadedProgram::load(kDomains + "/feeding/feeding.cbtl");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const auto& program = lp->program();
  std::vector<double> obs(program.observationWidth(), 0.0);
  const auto plate = *program.observationOffset("plateXY");
  const auto drink = *program.observationOffset("drinkXY");
  obs[plate] = 0.34;
  obs[plate + 1] = 0.30;
  obs[drink] = 0.34;
  obs[drink + 1] = 0.70;
  // No sauce on the table: the dip the robot may offer is "no dip" alone (the fifth Dip entry).
  obs[*program.observationOffset("dipChoices") + 4] = 1;
  for (const char* task : {"feedBite", "prepareDrink", "giveDrink"}) {
    const auto r = solveHard(*lp, static_cast<std::size_t>(lp->taskIndex(task)), obs);
    EXPECT_EQ(r.outcome, solver::SolveOutcome::Solved) << task;
  }
}

TEST(WorldBuiltins, HomeSceneQueriesPlacementAndBase) {
  auto lp = test::compileOrFail("h.cbtl", homePrelude() + R"(
require tableApproach: se2Distance(approachBase("table_top"), se2(0, -0.1, 0)) < 1e-9;
require bookApproachIsItsSurface: se2Distance(approachBase("book_6"), se2(0, -0.55, 0)) < 1e-9;
require bookOnShelf: supportSurface("book_0") == "shelf_layer_1";
require restsWhereItIs: restsOn("book_0", bodyPose("book_0"), "shelf_layer_1");
require notOnTheTable: not restsOn("book_0", bodyPose("book_0"), "table_top");
require originBaseIsFree: baseCollisionFree(se2(0, 0, 0));
require baseInTheBed: not baseCollisionFree(se2(2.4, 0, 0));
require baseCanDrive: basePathExists(se2(0, 0, 0), se2(0, -0.55, 0));
require unknownBody: not restsOn("noSuchBody", bodyPose("book_0"), "shelf_layer_1");
)");
  ASSERT_TRUE(lp->ok());
  expectAllHold(*lp, {});

  auto placing = test::compileOrFail("pl.cbtl", homePrelude() + R"(
var place : SE3;
require onTheBottomShelf: restsOn("book_0", place, "shelf_layer_0");
require clearOfEverything: placementClear("book_0", place, 0.1);
sample place ~ placementOn("shelf_layer_0", "book_0", 0.0);
)");
  ASSERT_TRUE(placing->ok());
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    EXPECT_EQ(solveHard(*placing, 0, {}, seed).outcome, solver::SolveOutcome::Solved) << seed;
  }
}

TEST(WorldBuiltins, AMissingSceneIsALoadErrorNamingTheFile) {
  auto lp = app::LoadedProgram::fromSource("m.cbtl", "domain m;\nworld \"no/such/scene.xml\";\n");
  ASSERT_FALSE(lp->ok());
  EXPECT_NE(lp->errors().find("no/such/scene.xml"), std::string::npos) << lp->errors();
}

TEST(WorldBuiltins, AWorldBuiltinWithoutASceneSaysWhatIsMissing) {
  auto lp = app::LoadedProgram::fromSource("n.cbtl", R"(domain n;
import std.kinova;
var q : Conf<gen3>;
require inLimits: withinJointLimits(q);
)");
  ASSERT_FALSE(lp->ok());
  EXPECT_NE(lp->errors().find("n.cbtl:4:"), std::string::npos) << lp->errors();
  EXPECT_NE(lp->errors().find("declare its scene with `world"), std::string::npos) << lp->errors();
}

TEST(WorldBuiltins, TheReferenceStateIsWhatTheBuiltinsSee) {
  auto lp = test::compileOrFail("r.cbtl", feedingPrelude() + R"(
require plateMoved: distance(bodyPose("plate").position, vec3(0.36, 0.5, 0.1625)) < 1e-6;
)");
  ASSERT_TRUE(lp->ok());
  EXPECT_FALSE(checkAll(*lp).at(0).second);
  world::WorldState s;
  s.arm = {0, -0.3491, 3.1416, -2.5482, 0, -0.8727, 1.5708};
  world::Pose3 p;
  p.position = Eigen::Vector3d(0.36, 0.5, 0.1625);
  s.objects["plate"] = p;
  ASSERT_TRUE(bind::setWorldReference(lp->program().host(), s));
  EXPECT_TRUE(checkAll(*lp).at(0).second);
  s.objects["noSuchObject"] = p;
  EXPECT_FALSE(bind::setWorldReference(lp->program().host(), s));
}

// std.collision's side grasp at yaw -pi/2 is the books' carry grasp the executor uses.
TEST(WorldBuiltins, SideGraspIsTheBooksCarryGrasp) {
  const world::Pose3 g = actions::bookToolInBody();
  char expected[256];
  std::snprintf(expected, sizeof expected, "poseQuat(vec3(%.9f, %.9f, %.9f), %.9f, %.9f, %.9f, %.9f)", g.position.x(),
                g.position.y(), g.position.z(), g.orientation.x(), g.orientation.y(), g.orientation.z(),
                g.orientation.w());
  auto lp = test::compileOrFail(
      "g.cbtl", homePrelude() +
                    "const inBody = relativePose(bodyPose(\"book_0\"), sideGraspPose(\"book_0\", -pi / 2));\n" +
                    "require same: distance(inBody.position, " + expected +
                    ".position) < 1e-6 and angleBetween(inBody, " + expected + ") < 1e-6;\n");
  ASSERT_TRUE(lp->ok());
  expectAllHold(*lp);
}
