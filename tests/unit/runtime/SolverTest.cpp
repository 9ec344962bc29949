// The sampling solver: the reference's small CSP, memory samplers, costs, outcomes, determinism.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
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
