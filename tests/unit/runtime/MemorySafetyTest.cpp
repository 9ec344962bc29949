// Programs that `cbtlc check` accepts must never corrupt memory or crash the runtime: every buffer is sized
// from the compiled program, or the program is rejected at load with a located error. Each case here once
// overflowed a fixed-size array (run under ASan/UBSan by `make asan`).
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/approach/Planner.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/Recheck.h"
#include "runtime/solver/Solver.h"

#include <gtest/gtest.h>

#include <string>

using namespace cbtl;

namespace {

solver::SolveResult solveFirstTask(const app::LoadedProgram& lp, const model::UserModel& user,
                                   std::uint64_t iters = 2000) {
  solver::SolverOptions o;
  o.maxIters = iters;
  solver::Solver s(o, 3);
  const auto csp = solver::makeCsp(lp.program(), 0, lp.instances(0), user, {}, solver::PersonalMode::Include,
                                   solver::CostKind::None);
  auto r = s.solve(csp);
  if (r.solved()) {
    const auto check = solver::recheck(csp, r.assignment);
    EXPECT_TRUE(check.holds()) << (check.violations.empty() ? "" : check.violations.front());
  }
  return r;
}

std::string familyProgram(int members) {
  return "domain big;\nvar flag[0 .. " + std::to_string(members - 1) + "] : bool;\nrequire last: flag[" +
         std::to_string(members - 1) + "];\nsample flag ~ uniform;\n";
}

}  // namespace

TEST(MemorySafety, AUniformFamilyWiderThanAnyFixedBufferIsDrawnWhole) {
  for (int members : {600, 5000}) {
    auto lp = test::compileOrFail("big.cbtl", familyProgram(members));
    ASSERT_TRUE(lp->ok());
    model::UserModel user(lp->graph());
    const auto r = solveFirstTask(*lp, user);
    ASSERT_TRUE(r.solved()) << members;
    EXPECT_EQ(r.assignment.size(), static_cast<std::size_t>(members));
    EXPECT_EQ(r.assignment.back(), 1.0);
  }
}

TEST(MemorySafety, AConstraintWithHundredsOfQuantifierBindersGetsAFrameOfItsSize) {
  std::string text = "domain deep;\nvar a : real in 0 .. 1 = 0.5;\nsample a ~ uniform;\nrequire many: ";
  for (int i = 0; i < 300; ++i) text += (i ? " and " : "") + std::string("(exists k in 0 .. 1: a >= 0)");
  text += ";\n";
  auto lp = test::compileOrFail("deep.cbtl", text);
  ASSERT_TRUE(lp->ok());
  EXPECT_GE(lp->program().frameSize(), 300u);
  model::UserModel user(lp->graph());
  EXPECT_TRUE(solveFirstTask(*lp, user).solved());
}

TEST(MemorySafety, AFunctionBodyThatIndexesAFamilyIsInTheConstraintsReadSet) {
  // The function is declared before the family on purpose: its body is lowered once the globals exist.
  const char* text = R"(domain fnread;
fn chosen(i: int) -> bool = flag[i];
var flag[0 .. 3] : bool;
var idx : int in 0 .. 3 = 0;
require pick: chosen(idx);
require notFirst: idx >= 2;
sample flag ~ uniform;
sample idx ~ uniform;
)";
  auto lp = test::compileOrFail("fnread.cbtl", text);
  ASSERT_TRUE(lp->ok());
  const auto& g = lp->graph();
  const ir::Constraint* pick = nullptr;
  for (const auto& c : g.constraints) {
    if (c.name == "pick") pick = &c;
  }
  ASSERT_NE(pick, nullptr);
  EXPECT_EQ(pick->vars.size(), 5u) << "idx and the four members of flag";
  model::UserModel user(lp->graph());
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    solver::SolverOptions o;
    o.maxIters = 500;
    solver::Solver s(o, seed);
    const auto csp = solver::makeCsp(lp->program(), 0, lp->instances(0), user, {}, solver::PersonalMode::Include,
                                     solver::CostKind::None);
    const auto r = s.solve(csp);
    ASSERT_TRUE(r.solved());
    EXPECT_TRUE(solver::recheck(csp, r.assignment).holds()) << "seed " << seed;
  }
}

TEST(MemorySafety, AValueWiderThanTheEvaluatorsLimitIsALoadErrorWithALocation) {
  // The language stops at vec<64> (E0309); a graph from elsewhere (or a future type) may not, and the runtime
  // must refuse it rather than overflow its evaluation buffers.
  auto lp = test::compileOrFail("wide.cbtl", "domain wide;\nvar v : vec<64>;\nrequire first: v.x >= 0;\n");
  ASSERT_TRUE(lp->ok());
  ir::ConstraintGraph graph = lp->graph();
  graph.variables[0].type.spelling = "vec<100>";
  try {
    rt::Program program(graph, rt::Builtins::standard());
    FAIL() << "a vec<100> was accepted";
  } catch (const rt::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("wide.cbtl:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("limit of 64"), std::string::npos) << e.what();
  }
}

TEST(MemorySafety, AQuantifierOverAHugeRunTimeRangeRejectsInsteadOfHanging) {
  const char* text = R"(domain huge;
var n : int in 0 .. 1000000000000 = 1000000000000;
require all: forall k in 0 .. n: k >= 0;
)";
  auto lp = test::compileOrFail("huge.cbtl", text);
  ASSERT_TRUE(lp->ok());
  model::UserModel user(lp->graph());
  const auto r = solveFirstTask(*lp, user, 10);
  EXPECT_FALSE(r.solved());
}

TEST(MemorySafety, TheLearnerSeesTheObservationOfTheStep) {
  const char* text = R"(domain handover;
observe hand : real;
var p : real in 0 .. 10 = 1;
sample p ~ uniform;
fn reach(x: real) -> real = x - hand;
feedback handed(at: real, ok: bool);
personal inReach(x: real) {
  when x ~ "p";
  model threshold(reach(x), -10 .. 10, below);
  learn handed(x, ok) => ok;
}
)";
  auto lp = test::compileOrFail("handover.cbtl", text);
  ASSERT_TRUE(lp->ok());
  model::UserModel user(lp->graph());
  approach::StepWorld world;
  world.observation.assign(lp->program().observationWidth(), 0.0);
  world.observation[*lp->program().observationOffset("hand")] = 4.0;
  const std::vector<sim::FeedbackEvent> events = {{"handed", {sim::Value::num(5.0), sim::Value::num(1)}},
                                                  {"handed", {sim::Value::num(9.0), sim::Value::num(0)}}};
  const auto report = lp->learner().learn(events, user, world);
  EXPECT_TRUE(report.problems.empty()) << report.problems.front();
  EXPECT_EQ(report.labels, 2u);
  // Without a world the observation reads as zero: no crash, a different feature.
  model::UserModel blind(lp->graph());
  EXPECT_EQ(lp->learner().learn(events, blind).labels, 2u);
  // The observation moved the features: with the hand at 4 the examples are 1 (liked) and 5 (not), so a
  // feature of 4.5 is doubtful; without it they are 5 and 9, and 4.5 is below the liked example.
  const double seen = user.generator(0).mutableFactors("")[0].probability(4.5);
  const double unseen = blind.generator(0).mutableFactors("")[0].probability(4.5);
  EXPECT_LT(seen, unseen);
}
