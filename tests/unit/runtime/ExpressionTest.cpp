// Compiled expressions and personalization against small programs.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/core/Personalization.h"
#include "runtime/model/UserModel.h"

#include <gtest/gtest.h>

using namespace cbtl;

namespace {

// Evaluates a constraint on an assignment given as the flat layout of all variables (declaration order).
bool holds(app::LoadedProgram& lp, std::vector<double> x, std::size_t constraint = 0) {
  const auto& program = lp.program();
  EXPECT_EQ(x.size(), program.assignmentWidth());
  x.resize(program.assignmentWidth());
  std::vector<double> frame(64), obs(program.observationWidth() + 1);
  rt::EvalContext ctx{x.data(), obs.data(), frame.data()};
  return program.pool().evalBool(program.constraints().at(constraint).root, ctx);
}

}  // namespace

TEST(Expression, ArithmeticComparisonAndLogic) {
  auto lp = test::compileOrFail("e.cbtl",
                                "domain e; var a : real in 0 .. 10; var b : int in 0 .. 10;\n"
                                "require a * 2 + 1 > b and not (b == 3) => a - b <= 4;\n");
  ASSERT_TRUE(lp->ok());
  EXPECT_TRUE(holds(*lp, {2.0, 4}));
  EXPECT_FALSE(holds(*lp, {9.0, 4}));  // premise holds, 9 - 4 > 4
  EXPECT_TRUE(holds(*lp, {9.0, 3}));   // b == 3: the premise is false
}

TEST(Expression, QuantifiersFamiliesConstTablesAndInlinedFunctions) {
  auto lp = test::compileOrFail("q.cbtl", R"(domain q;
enum Color { red, green, blue }
const weight[Color] : real = [1.0, 2.0, 3.0];
fn twice(v: real) -> real = v * 2;
var pick[Color] : bool = false;
var c : Color = red;
require forall k in Color: pick[k] => twice(weight[k]) <= 4.0;
require exists k in Color: pick[k];
require weight[c] in 1.5 .. 2.5;
)");
  ASSERT_TRUE(lp->ok());
  // Variables: pick[red], pick[green], pick[blue], c. The top-level forall is unrolled into constraints
  // 0 .. 2 (one per colour); 3 is the exists (evaluated at run time), 4 the table look-up.
  EXPECT_TRUE(holds(*lp, {1, 1, 0, 1}, 1));
  EXPECT_FALSE(holds(*lp, {0, 0, 1, 1}, 2));  // twice(3) > 4
  EXPECT_TRUE(holds(*lp, {0, 0, 0, 1}, 2));
  EXPECT_FALSE(holds(*lp, {0, 0, 0, 1}, 3));
  EXPECT_TRUE(holds(*lp, {0, 1, 0, 1}, 3));
  EXPECT_TRUE(holds(*lp, {0, 0, 0, 1}, 4));   // c = green, weight 2
  EXPECT_FALSE(holds(*lp, {0, 0, 0, 2}, 4));  // c = blue, weight 3
}

TEST(Expression, VectorsAndBuiltins) {
  auto lp = test::compileOrFail("v.cbtl", R"(domain v;
import std.geometry;
var p : vec<2> in [0 .. 10, 0 .. 10];
require distance(p, vec2(3, 4)) < 1 and p.x > 2.5;
)");
  ASSERT_TRUE(lp->ok());
  EXPECT_TRUE(holds(*lp, {3.2, 4.1}));
  EXPECT_FALSE(holds(*lp, {2.4, 4.0}));
  EXPECT_FALSE(holds(*lp, {6.0, 8.0}));
}

TEST(Expression, UnknownBuiltinIsAnErrorWithALocation) {
  auto lp = app::LoadedProgram::fromSource("b.cbtl", R"(domain b;
extern fn mystery(x: real) -> real;
var a : real in 0 .. 1;
require mystery(a) > 0;
)");
  EXPECT_FALSE(lp->ok());
  EXPECT_NE(lp->errors().find("b.cbtl:4:"), std::string::npos) << lp->errors();
  EXPECT_NE(lp->errors().find("mystery"), std::string::npos) << lp->errors();
}

TEST(Personalization, PatternsCapturesAndTypesSelectTuples) {
  auto lp = test::compileOrFail("p.cbtl", R"(domain p;
enum Ing { salt, pepper }
var temp[Ing] : real in 0 .. 5;
var qty[Ing] : real in 0 .. 2;
var count[Ing] : int in 0 .. 2;
var other : real in 0 .. 1;
feedback liked(i: Ing, t: real, q: real, ok: bool);
personal tasty(t: real, q: real) {
  when t ~ "temp[{i}]", q ~ "qty[{i}]";
  model a = interval(t, 0 .. 5) * b = interval(q, 0 .. 2) per i;
  learn liked(i, t, q, ok) => a: ok, b: ok;
}
personal anyReal(v: real) {
  when v ~ regex "o.*";
  model interval(v, 0 .. 1);
  learn liked(_, v, _, ok) => ok;
}
)");
  ASSERT_TRUE(lp->ok());
  const auto& inst = lp->instances(0);
  ASSERT_EQ(inst.size(), 3u);  // the capture must agree: temp[salt] with qty[salt] only; count[] has the wrong type
  EXPECT_EQ(inst[0].name, "tasty(temp[salt], qty[salt])");
  EXPECT_EQ(inst[1].name, "tasty(temp[pepper], qty[pepper])");
  EXPECT_EQ(inst[2].name, "anyReal(other)");
  EXPECT_EQ(inst[1].key.size(), 1u);
  EXPECT_EQ(inst[1].key[0].text, "pepper");
  // Learning puts the labels under the key the instances read.
  model::UserModel user(lp->graph());
  const auto report = lp->learner().learn(
      {sim::FeedbackEvent{
          "liked", {sim::Value::name("pepper"), sim::Value::num(2.0), sim::Value::num(1.0), sim::Value::num(1)}}},
      user);
  EXPECT_TRUE(report.problems.empty());
  EXPECT_EQ(report.labels, 3u);  // a and b of tasty, and anyReal
  EXPECT_EQ(user.generator(0).keys().count("pepper"), 1u);
  const auto bad = lp->learner().learn(
      {sim::FeedbackEvent{"liked",
                          {sim::Value::name("cumin"), sim::Value::num(2.0), sim::Value::num(1.0), sim::Value::num(1)}}},
      user);
  ASSERT_FALSE(bad.problems.empty());
  EXPECT_NE(bad.problems[0].find("cumin"), std::string::npos);
}

TEST(Personalization, CookingHasOneInstancePerIngredient) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const auto& inst = lp->instances(0);
  ASSERT_EQ(inst.size(), 4u);
  EXPECT_EQ(inst[0].name, "userEnjoysMeal(meal, used[salt], startTick[salt], totalTicks, quantity[salt])");
  EXPECT_EQ(inst[0].captures, std::vector<std::string>{"salt"});
  EXPECT_TRUE(inst[0].guard.has_value());
  EXPECT_EQ(inst[0].hyperedge.size(), 5u);
}
