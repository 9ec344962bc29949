// The sampling solver: the reference's small CSP, memory samplers, costs, outcomes, determinism, guided and
// dependent draws, and which personalized constraints each kind of solve keeps.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/PersonalEvaluator.h"
#include "runtime/solver/Recheck.h"
#include "runtime/solver/Solver.h"

#include <gtest/gtest.h>

using namespace cbtl;

namespace {

struct Tiny {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("tiny.cbtl", test::kTinySource);
  model::UserModel user{lp->graph()};
  Tiny() {
    // Learned: y <= theta with theta in [1, 3]; accepted (P >= 0.5) for y up to about 2.
    auto& f = user.generator(0).mutableFactors("");
    f[0].observe(1.0, true);
    f[0].observe(3.0, false);
  }
  solver::Csp csp(solver::PersonalMode personal, solver::CostKind cost = solver::CostKind::None) const {
    return solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, personal, cost);
  }
  double value(const std::vector<double>& x, const char* name) const {
    for (const auto& v : lp->graph().variables) {
      if (v.name == name) return x[lp->program().slot(v.id).offset];
    }
    ADD_FAILURE() << name;
    return 0;
  }
};

}  // namespace

TEST(Solver, SolvesTheReferenceSmallCsp) {
  Tiny t;
  solver::Solver s({}, 7);
  const auto r = s.solve(t.csp(solver::PersonalMode::Include));
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  const double x = t.value(r.assignment, "x"), y = t.value(r.assignment, "y");
  EXPECT_LT(x, y);
  EXPECT_LE(y, 2.0 + 1e-2);
  // The initial assignment (x = y = 0) violates x < y, so the walk had to move.
  EXPECT_GT(r.iterations, 1u);
}

TEST(Solver, MemorySamplersAloneResolveARegeneratedCsp) {
  Tiny t;
  solver::Solver s({}, 3);
  ASSERT_TRUE(s.solve(t.csp(solver::PersonalMode::Include)).solved());
  EXPECT_GT(s.memoryEntries(), 0u);
  solver::Csp again = t.csp(solver::PersonalMode::Include);
  again.samplers.clear();  // no user samplers: only what the solver remembers
  const auto r = s.solve(again);
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  EXPECT_LT(t.value(r.assignment, "x"), t.value(r.assignment, "y"));
}

TEST(Solver, NoSamplersAndNoMemoryIsReported) {
  Tiny t;
  solver::Solver s({}, 3);
  solver::Csp c = t.csp(solver::PersonalMode::Exclude);
  c.samplers.clear();
  EXPECT_EQ(s.solve(c).outcome, solver::SolveOutcome::NoSamplers);
}

TEST(Solver, InfeasibleWithinBudgetNamesTheRejectingConstraint) {
  auto lp = test::compileOrFail("inf.cbtl",
                                "domain inf; var a : real in 0 .. 1; require never: a > 2; sample a ~ uniform;\n");
  model::UserModel user(lp->graph());
  solver::SolverOptions o;
  o.maxIters = 500;
  solver::Solver s(o, 1);
  const auto c = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include,
                                 solver::CostKind::None);
  const auto r = s.solve(c);
  EXPECT_EQ(r.outcome, solver::SolveOutcome::InfeasibleWithinBudget);
  EXPECT_EQ(r.iterations, 500u);
  ASSERT_EQ(r.constraints.size(), 1u);
  EXPECT_EQ(r.constraints[0].rejections, 500u);
  EXPECT_EQ(solver::constraintName(c, r.constraints[0].ref), "never");
  EXPECT_EQ(solver::constraintLocation(c, r.constraints[0].ref), "inf.cbtl:1:37");
}

TEST(Solver, SamplersThatAlwaysFailAreStuck) {
  auto lp = test::compileOrFail("stuck.cbtl",
                                "domain stuck; var a : int in 0 .. 5; require a > 0;\n"
                                "sample a ~ uniformInt(3, 1);\n");
  model::UserModel user(lp->graph());
  solver::Solver s({}, 1);
  const auto c = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include,
                                 solver::CostKind::None);
  EXPECT_EQ(s.solve(c).outcome, solver::SolveOutcome::SamplersStuck);
}

TEST(Solver, EntropyCostPrefersUncertainValues) {
  Tiny t;
  solver::SolverOptions o;
  o.numImprovements = 200;
  o.maxImprovementAttempts = 5000;
  solver::Solver s(o, 11);
  const auto r = s.solve(t.csp(solver::PersonalMode::Exclude, solver::CostKind::Entropy));
  ASSERT_TRUE(r.solved());
  // P(y <= theta) ramps from 1 at y = 1 to 0 at y = 3: entropy peaks at y = 2.
  EXPECT_NEAR(t.value(r.assignment, "y"), 2.0, 0.25);
  EXPECT_LT(r.cost, 0.05);
}

TEST(Solver, SameSeedSameResult) {
  Tiny t;
  solver::Solver a({}, 42), b({}, 42), c({}, 43);
  const auto ra = a.solve(t.csp(solver::PersonalMode::Include));
  const auto rb = b.solve(t.csp(solver::PersonalMode::Include));
  const auto rc = c.solve(t.csp(solver::PersonalMode::Include));
  EXPECT_EQ(ra.assignment, rb.assignment);
  EXPECT_EQ(ra.iterations, rb.iterations);
  EXPECT_NE(ra.assignment, rc.assignment);
}

TEST(Solver, SolutionsMemoryRemembersOnlyAcceptedSolutions) {
  Tiny t;
  solver::SolverOptions o;
  o.memoryPolicy = solver::MemoryPolicy::Solutions;
  solver::Solver s(o, 3);
  ASSERT_TRUE(s.solve(t.csp(solver::PersonalMode::Include)).solved());
  EXPECT_EQ(s.memoryEntries(), 2u) << "one solution: one entry for each of the two constraints";
  solver::Csp again = t.csp(solver::PersonalMode::Include);
  again.samplers.clear();
  const auto r = s.solve(again);
  ASSERT_TRUE(r.solved());
  // The initial candidate (x = y = 0) fails; one move from memory restores solution values that satisfy both.
  EXPECT_EQ(r.iterations, 2u);
}

TEST(Solver, ExploitingWithoutADeclaredCostPicksTheLikeliestSolution) {
  Tiny t;
  const solver::Csp c = t.csp(solver::PersonalMode::Include, solver::CostKind::Declared);
  ASSERT_EQ(c.cost, solver::CostKind::Likelihood);
  solver::Solver s({}, 5);
  const auto r = s.solve(c);
  ASSERT_TRUE(r.solved());
  // Accepted (P >= 0.5) up to y = 2, but certain only up to y = 1: nothing less than certain is returned when a
  // certain solution is this easy to find, and the search stops there.
  EXPECT_LE(t.value(r.assignment, "y"), 1.0);
  EXPECT_EQ(r.cost, 0.0);
  EXPECT_LT(r.iterations, solver::SolverOptions{}.maxImprovementAttempts);
}

TEST(Solver, ProposalsAPersonalizedConstraintRejectsAreDrawnAgain) {
  // y ~ uniform in [0, 10] is accepted by smallY only up to y = 2: four proposals in five would be rejected.
  // y's sampler alone decides smallY, so the walk redraws y until smallY accepts it (up to 16 draws). `never`
  // keeps the walk going for the whole budget.
  auto lp = test::compileOrFail("guided.cbtl", R"(domain guided;
var y : real in 0 .. 10 = 0;
var z : real in 0 .. 1 = 0;
require never: z > 2;
sample y ~ uniform;
sample z ~ uniform;
feedback rated(v: real, good: bool);
personal smallY(v: real) {
  when v ~ "y";
  model threshold(v, 0 .. 10, below);
  learn rated(v, good) => good;
}
)");
  model::UserModel user(lp->graph());
  auto& f = user.generator(0).mutableFactors("");
  f[0].observe(1.0, true);
  f[0].observe(3.0, false);
  solver::SolverOptions o;
  o.maxIters = 400;
  solver::Solver s(o, 9);
  const auto c = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include,
                                 solver::CostKind::None);
  const auto r = s.solve(c);
  ASSERT_EQ(r.outcome, solver::SolveOutcome::InfeasibleWithinBudget);
  ASSERT_TRUE(r.constraints[0].ref.personal());
  EXPECT_GT(r.constraints[0].evaluations, 100u);
  EXPECT_LT(r.constraints[0].rejections * 10, r.constraints[0].evaluations)
      << "fewer than one proposal in ten reaches the check rejected";
}

TEST(Solver, SamplersThatReadAMovedVariableAreRedrawnInTheSameMove) {
  auto lp = test::compileOrFail("chain.cbtl",
                                "domain chain;\n"
                                "var x : real in 0 .. 10 = 0;\n"
                                "var y : real in 0 .. 20 = 1;\n"
                                "require follows: y == x + 1;\n"
                                "require never: x > 20;\n"
                                "sample x ~ uniform;\n"
                                "sample y ~ uniformReal(x + 1, x + 1);\n");
  model::UserModel user(lp->graph());
  solver::SolverOptions o;
  o.maxIters = 300;
  solver::Solver s(o, 4);
  const auto c = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include,
                                 solver::CostKind::None);
  const auto r = s.solve(c);
  ASSERT_EQ(r.outcome, solver::SolveOutcome::InfeasibleWithinBudget);
  ASSERT_EQ(solver::constraintName(c, r.constraints[0].ref), "follows");
  // Every move of x draws y for the new x: no candidate pairs a new x with the y of the old one.
  EXPECT_GT(r.constraints[0].evaluations, 100u);
  EXPECT_EQ(r.constraints[0].rejections, 0u);
}

namespace {

// Two generators on two variables; CBTL explores `near` only where it accepts it.
const char* kTwoGeneratorsSource = R"(domain two;
var a : real in 0 .. 10 = 1;
var b : real in 0 .. 10 = 1;
sample a ~ uniform;
sample b ~ uniform;
feedback rated(v: real, good: bool);
personal near(v: real) {
  when v ~ "a";
  model interval(v, 0 .. 10);
  explore accepted;
  learn rated(v, good) => good;
}
personal far(v: real) {
  when v ~ "b";
  model interval(v, 0 .. 10);
  learn rated(v, good) => good;
}
)";

}  // namespace

TEST(Solver, CbtlExplorationKeepsTheConstraintsOfGeneratorsThatExploreWhereTheyAccept) {
  auto lp = test::compileOrFail("two.cbtl", kTwoGeneratorsSource);
  ASSERT_TRUE(lp->graph().generators[0].exploreAccepted);
  ASSERT_FALSE(lp->graph().generators[1].exploreAccepted);
  model::UserModel user(lp->graph());
  for (std::uint32_t g : {0u, 1u}) {  // each accepts [1, 2] (P = 1) and nothing beyond 3 or below 0.5
    auto& f = user.generator(g).mutableFactors("");
    f[0].observe(1.0, true);
    f[0].observe(2.0, true);
    f[0].observe(3.0, false);
    f[0].observe(0.5, false);
  }
  const auto personalNames = [&](const solver::Csp& c) {
    std::vector<std::string> names;
    for (const auto& ref : c.constraints) {
      if (ref.personal()) names.push_back(solver::constraintName(c, ref));
    }
    return names;
  };
  using solver::CostKind;
  using solver::PersonalMode;
  const auto explore =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, PersonalMode::Exclude, CostKind::Entropy);
  EXPECT_EQ(personalNames(explore), std::vector<std::string>{"near(a)"});
  EXPECT_EQ(explore.scoredInstances.size(), 2u) << "both still steer the entropy";
  const auto freeExplore =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, PersonalMode::Exclude, CostKind::Declared);
  EXPECT_TRUE(personalNames(freeExplore).empty()) << "only CBTL's exploration keeps them";
  const auto exploit =
      solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, PersonalMode::Include, CostKind::Declared);
  EXPECT_EQ(personalNames(exploit).size(), 2u);

  solver::SolverOptions o;
  o.numImprovements = 100;
  o.maxImprovementAttempts = 400;
  solver::Solver s(o, 2);
  const auto r = s.solve(explore);
  ASSERT_TRUE(r.solved());
  const double a = r.assignment[lp->program().slot(lp->graph().variables[0].id).offset];
  EXPECT_GE(a, 0.75);  // accepted: P(a) >= 0.5 on [0.75, 2.5]
  EXPECT_LE(a, 2.5);
  // The independent re-check holds the solution to exactly the personalized constraints the CSP has.
  std::vector<double> farOutside = r.assignment;
  farOutside[lp->program().slot(lp->graph().variables[1].id).offset] = 9.0;  // far(b) rejects 9
  EXPECT_TRUE(solver::recheck(explore, farOutside).holds());
  EXPECT_FALSE(solver::recheck(exploit, farOutside).holds());
}

TEST(Solver, BeforeItsFirstPositiveAGeneratorThatExploresWhereItAcceptsSteersNoExploration) {
  auto lp = test::compileOrFail("two.cbtl", kTwoGeneratorsSource);
  model::UserModel user(lp->graph());
  const auto& instances = lp->instances(0);
  const auto instanceNamed = [&](const std::string& name) {
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      if (instances[i].name == name) return i;
    }
    ADD_FAILURE() << name;
    return 0u;
  };
  const std::uint32_t near = instanceNamed("near(a)"), far = instanceNamed("far(b)");
  const auto valueAt = [&](std::uint32_t instance, double v) {
    std::vector<double> x = lp->program().initialAssignment();
    x[lp->program().slot(lp->graph().variables[0].id).offset] = v;
    x[lp->program().slot(lp->graph().variables[1].id).offset] = v;
    std::vector<double> frame(64), obs(lp->program().observationWidth() + 1);
    rt::EvalContext ctx{x.data(), obs.data(), frame.data()};
    solver::PersonalEvaluator evaluator(lp->program(), instances, user);
    return evaluator.evaluate(instance, ctx);
  };
  // No data: both accept everything; only the one that explores anywhere has uncertainty to follow (the middle of
  // the bounds under the uniform prior over intervals).
  EXPECT_DOUBLE_EQ(valueAt(near, 5).probability, 1.0);
  EXPECT_DOUBLE_EQ(valueAt(near, 5).posterior, 1.0);
  EXPECT_DOUBLE_EQ(valueAt(far, 5).probability, 1.0);
  EXPECT_NEAR(valueAt(far, 5).posterior, 0.5, 1e-12);
  // A refusal: near(a) rejects its neighbourhood and still steers nothing elsewhere.
  user.generator(0).mutableFactors("")[0].observe(5.0, false);
  EXPECT_DOUBLE_EQ(valueAt(near, 5.05).probability, 0.0);
  EXPECT_DOUBLE_EQ(valueAt(near, 8).posterior, 1.0);
  // Once something is liked, the accepted reading is the full posterior: both generators follow it alike.
  for (std::uint32_t g : {0u, 1u}) user.generator(g).mutableFactors("")[0].observe(2.0, true);
  user.generator(1).mutableFactors("")[0].observe(5.0, false);
  for (double v : {1.0, 3.0, 4.9}) {
    EXPECT_DOUBLE_EQ(valueAt(near, v).posterior, valueAt(near, v).probability) << v;
    EXPECT_DOUBLE_EQ(valueAt(near, v).posterior, valueAt(far, v).posterior) << v;
  }
  EXPECT_NEAR(valueAt(near, 1.0).posterior, 0.5, 1e-12);
}
