// The solver with a staged plan (runtime/solver/StagedPlan.h): PlanExecutes is checked last and charged with
// its rejections by failing action; ties after the first solution defer their dry runs, and the result is still
// a candidate whose plan runs.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/Solver.h"
#include "runtime/solver/StagedPlan.h"

#include <gtest/gtest.h>

#include <functional>

using namespace cbtl;

namespace {

// x < y is the only hard constraint; the cost is the same for every candidate, so every solution after the
// first ties it.
constexpr const char* kTieSource = R"(domain ties;
var x : real in 0 .. 10 = 0;
var y : real in 0 .. 10 = 0;
require order: x < y;
sample x ~ uniform;
sample y ~ uniform;
minimize 0 * y;
)";

// A plan of one stage whose dry run is decided by `runs` on the candidate's y.
class FakePlan final : public solver::StagedPlan {
 public:
  FakePlan(std::vector<ir::VarId> reads, std::size_t ySlot, std::function<bool(double)> runs)
      : reads_(std::move(reads)), ySlot_(ySlot), runs_(std::move(runs)) {}

  std::size_t stageCount() const override { return 1; }
  const std::vector<ir::VarId>& readsBefore(std::size_t) const override { return none_; }
  const std::vector<ir::VarId>& reads() const override { return reads_; }
  void changed() override {}
  bool enterStage(std::size_t, const rt::EvalContext&) override { return true; }
  void enterRecentStage(std::size_t) override {}
  sim::PlanVerdict check(const rt::EvalContext& ctx) override {
    ++checks;
    const double y = ctx.assignment[ySlot_];
    sim::PlanVerdict v;
    v.executes = runs_(y);
    if (!v.executes) {
      v.action = "moveArm";
      v.status = "no collision-free path";
      v.detail = "blocked";
    } else {
      accepted.push_back(y);
    }
    return v;
  }
  sim::PlanVerdict stageFailure() const override { return {}; }

  int checks = 0;
  std::vector<double> accepted;  // y of every candidate whose dry run passed, in order

 private:
  std::vector<ir::VarId> none_, reads_;
  std::size_t ySlot_;
  std::function<bool(double)> runs_;
};

struct TieProblem {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("ties.cbtl", kTieSource);
  model::UserModel user{lp->graph()};

  std::size_t slotOf(const char* name) const {
    for (const auto& v : lp->graph().variables)
      if (v.name == name) return lp->program().slot(v.id).offset;
    ADD_FAILURE() << name;
    return 0;
  }
  std::vector<ir::VarId> allVars() const {
    std::vector<ir::VarId> out;
    for (const auto& v : lp->graph().variables) out.push_back(v.id);
    return out;
  }
  solver::Csp csp(solver::StagedPlan& plan, solver::CostKind cost) const {
    solver::Csp c = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include, cost);
    c.plan = &plan;
    c.constraints.push_back({solver::ConstraintKind::PlanExecutes, 0, 0xfeedULL});
    c.constraintStage.assign(c.constraints.size(), solver::kAnyStage);
    c.samplerStage.assign(c.samplers.size(), solver::kAnyStage);
    c.instanceStage.assign(c.instances->size(), solver::kAnyStage);
    return c;
  }
};

const solver::ConstraintStats* statsOf(const solver::SolveResult& r, solver::ConstraintKind kind) {
  for (const auto& c : r.constraints)
    if (c.ref.kind == kind) return &c;
  return nullptr;
}

}  // namespace

TEST(StagedPlanSolver, OnlyACandidateWhosePlanRunsIsAccepted) {
  TieProblem p;
  const std::size_t y = p.slotOf("y");
  FakePlan plan(p.allVars(), y, [](double v) { return v > 9.0; });
  solver::Solver s({}, 5);
  const auto r = s.solve(p.csp(plan, solver::CostKind::None));
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  EXPECT_GT(r.assignment[y], 9.0);
  EXPECT_LT(r.assignment[p.slotOf("x")], r.assignment[y]);
  const auto* planStats = statsOf(r, solver::ConstraintKind::PlanExecutes);
  ASSERT_NE(planStats, nullptr);
  EXPECT_GT(planStats->rejections, 0u);
  // The dry run is reached only by candidates that satisfy x < y: it is checked last.
  const auto* order = statsOf(r, solver::ConstraintKind::Hard);
  ASSERT_NE(order, nullptr);
  EXPECT_EQ(static_cast<std::uint64_t>(plan.checks), planStats->evaluations);
  EXPECT_LT(planStats->evaluations, order->evaluations);
  // Rejections are reported by failing action and status, with an example.
  ASSERT_EQ(r.planFailures.count("moveArm: no collision-free path"), 1u);
  const auto& f = r.planFailures.at("moveArm: no collision-free path");
  EXPECT_EQ(f.count, planStats->rejections);
  EXPECT_NE(f.example.find("blocked"), std::string::npos);
}

TEST(StagedPlanSolver, ANeverRunningPlanLeavesTheRequestUnsolved) {
  TieProblem p;
  FakePlan plan(p.allVars(), p.slotOf("y"), [](double) { return false; });
  solver::SolverOptions o;
  o.maxIters = 300;
  solver::Solver s(o, 2);
  const auto r = s.solve(p.csp(plan, solver::CostKind::None));
  EXPECT_EQ(r.outcome, solver::SolveOutcome::InfeasibleWithinBudget);
  EXPECT_GT(plan.checks, 0);
}

TEST(StagedPlanSolver, TiesDeferTheirDryRunsAndTheResultsPlanRuns) {
  TieProblem p;
  const std::size_t y = p.slotOf("y");
  FakePlan plan(p.allVars(), y, [](double v) { return v > 5.0; });
  solver::SolverOptions o;
  o.maxIters = 5000;
  o.maxImprovementAttempts = 400;
  o.numImprovements = 1000000;
  solver::Solver s(o, 11);
  const auto r = s.solve(p.csp(plan, solver::CostKind::Declared));
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  EXPECT_GT(r.assignment[y], 5.0);
  // Hundreds of ties were found after the first solution, but at most kMaxDeferredTies of them were dry-run
  // beyond those checked before the first solution.
  EXPECT_GT(r.improvements, 50u);
  ASSERT_FALSE(plan.accepted.empty());
  const auto* planStats = statsOf(r, solver::ConstraintKind::PlanExecutes);
  ASSERT_NE(planStats, nullptr);
  EXPECT_LE(planStats->evaluations, planStats->rejections + 1 + 16);
  // The latest deferred tie whose plan runs is the result: the last plan accepted.
  EXPECT_EQ(plan.accepted.back(), r.assignment[y]);
}

TEST(StagedPlanSolver, WhenNoDeferredTieRunsTheFirstVerifiedSolutionStands) {
  TieProblem p;
  const std::size_t y = p.slotOf("y");
  int passes = 0;
  // Only the first dry run that reaches y > 5 succeeds; every later one fails.
  FakePlan plan(p.allVars(), y, [&passes](double v) { return v > 5.0 && passes++ == 0; });
  solver::SolverOptions o;
  o.maxIters = 3000;
  o.maxImprovementAttempts = 200;
  o.numImprovements = 1000000;
  solver::Solver s(o, 4);
  const auto r = s.solve(p.csp(plan, solver::CostKind::Declared));
  ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved);
  ASSERT_EQ(plan.accepted.size(), 1u);
  EXPECT_EQ(r.assignment[y], plan.accepted.front());
}

TEST(StagedPlanSolver, TheSameSeedGivesTheSameResult) {
  TieProblem p;
  const std::size_t y = p.slotOf("y");
  auto solveOnce = [&] {
    FakePlan plan(p.allVars(), y, [](double v) { return v > 7.0; });
    solver::Solver s({}, 9);
    return s.solve(p.csp(plan, solver::CostKind::Declared)).assignment;
  };
  EXPECT_EQ(solveOnce(), solveOnce());
}
