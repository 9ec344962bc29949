// The IR validator on hand-built graphs: a valid one passes, and each kind of damage is reported.
#include "ir/Validator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbtl::ir {
namespace {

Span at(std::uint32_t line) { return Span{"t.cbtl", line, 1, line, 2}; }

Expr var(VarId id) {
  Expr e;
  e.op = Op::Var;
  e.id = id;
  e.type = {TypeKind::Real, "real"};
  return e;
}

Expr less(Expr a, Expr b) {
  Expr e;
  e.op = Op::Lt;
  e.type = {TypeKind::Bool, "bool"};
  e.children.push_back(std::move(a));
  e.children.push_back(std::move(b));
  return e;
}

// Two variables, one constraint over both, a sampler, a cost, a generator, and a task holding everything.
ConstraintGraph validGraph() {
  ConstraintGraph g;
  for (VarId i = 0; i < 2; ++i) {
    Variable v;
    v.id = i;
    v.name = i == 0 ? "x" : "y";
    v.type = {TypeKind::Real, "real"};
    v.span = at(i + 1);
    g.variables.push_back(v);
  }
  Constraint c;
  c.id = 0;
  c.name = "xy";
  c.expr = less(var(0), var(1));
  c.vars = {0, 1};
  c.span = at(3);
  g.constraints.push_back(c);
  Sampler s;
  s.id = 0;
  s.sampler = "uniform";
  s.writes = {0, 1};
  g.samplers.push_back(s);
  Cost cost;
  cost.expr = var(0);
  cost.vars = {0};
  g.costs.push_back(cost);
  Generator gen;
  gen.name = "g";
  gen.params.push_back({"p", {TypeKind::Real, "real"}});
  gen.patterns.push_back({"p", 0, PatternKind::Glob, "*x", at(4)});
  g.generators.push_back(gen);
  Task t;
  t.name = "main";
  t.vars = {0, 1};
  t.constraints = {0};
  t.samplers = {0};
  t.costs = {0};
  g.tasks.push_back(t);
  return g;
}

bool mentions(const std::vector<std::string>& problems, const std::string& part) {
  return std::any_of(problems.begin(), problems.end(),
                     [&](const std::string& p) { return p.find(part) != std::string::npos; });
}

TEST(Validator, AcceptsAValidGraph) { EXPECT_TRUE(validate(validGraph()).empty()); }

TEST(Validator, VariableIdsAndSpans) {
  ConstraintGraph g = validGraph();
  g.variables[1].id = 7;
  g.variables[0].span = Span{};
  const auto p = validate(g);
  EXPECT_TRUE(mentions(p, "variable 1 has id 7"));
  EXPECT_TRUE(mentions(p, "variable x has no span"));
}

TEST(Validator, HyperedgeMustEqualTheVariablesRead) {
  ConstraintGraph g = validGraph();
  g.constraints[0].vars = {0};
  EXPECT_TRUE(mentions(validate(g), "hyperedge differs"));
}

TEST(Validator, ConstraintReadingAnUnknownVariable) {
  ConstraintGraph g = validGraph();
  g.constraints[0].expr = less(var(0), var(9));
  g.constraints[0].vars = {0, 9};
  const auto p = validate(g);
  EXPECT_TRUE(mentions(p, "reads unknown variable 9"));
  EXPECT_TRUE(mentions(p, "reads a variable outside the task"));
}

TEST(Validator, ConstraintsAreBoolWithIdsAndSpans) {
  ConstraintGraph g = validGraph();
  g.constraints[0].expr = var(0);
  g.constraints[0].vars = {0};
  g.constraints[0].id = 3;
  g.constraints[0].span = Span{};
  const auto p = validate(g);
  EXPECT_TRUE(mentions(p, "is real, not bool"));
  EXPECT_TRUE(mentions(p, "constraint 0 has id 3"));
  EXPECT_TRUE(mentions(p, "constraint xy has no span"));
}

TEST(Validator, SamplersWriteKnownVariables) {
  ConstraintGraph g = validGraph();
  g.samplers[0].writes = {};
  EXPECT_TRUE(mentions(validate(g), "writes no variable"));
  g.samplers[0].writes = {5};
  const auto p = validate(g);
  EXPECT_TRUE(mentions(p, "writes unknown variable 5"));
  EXPECT_TRUE(mentions(p, "writes a variable outside the task"));
}

TEST(Validator, TasksListKnownItemsAndUniqueNames) {
  ConstraintGraph g = validGraph();
  g.tasks[0].vars = {0, 1, 4};
  g.tasks[0].constraints = {0, 2};
  g.tasks[0].samplers = {0, 3};
  g.tasks[0].costs = {0, 6};
  auto p = validate(g);
  EXPECT_TRUE(mentions(p, "task main lists unknown variable 4"));
  EXPECT_TRUE(mentions(p, "task main lists unknown constraint 2"));
  EXPECT_TRUE(mentions(p, "task main lists unknown sampler 3"));
  EXPECT_TRUE(mentions(p, "task main lists unknown cost 6"));
  g = validGraph();
  g.variables[1].name = "x";
  EXPECT_TRUE(mentions(validate(g), "two variables named x"));
}

TEST(Validator, ConstraintOutsideItsTask) {
  ConstraintGraph g = validGraph();
  g.tasks[0].vars = {0};
  EXPECT_TRUE(mentions(validate(g), "constraint xy reads a variable outside the task"));
}

TEST(Validator, GeneratorsHaveArityAndCompilingPatterns) {
  ConstraintGraph g = validGraph();
  g.generators[0].patterns[0].text = "{unclosed";
  g.generators[0].patterns.push_back({"q", 3, PatternKind::Regex, "(", at(5)});
  auto p = validate(g);
  EXPECT_TRUE(mentions(p, "pattern {unclosed does not compile"));
  EXPECT_TRUE(mentions(p, "pattern ( does not compile"));
  EXPECT_TRUE(mentions(p, "pattern for unknown parameter"));
  g = validGraph();
  g.generators[0].params.clear();
  g.generators[0].patterns.clear();
  EXPECT_TRUE(mentions(validate(g), "generator g has arity 0"));
}

// validGraph with a clearance and a skill instance whose one action is an allow block for it around a call.
ConstraintGraph graphWithAllow() {
  ConstraintGraph g = validGraph();
  g.clearances.push_back({"person", {"user"}, 0.05, at(6)});
  Action call;
  call.kind = ActionKind::Call;
  call.name = "say";
  call.span = at(8);
  Action allow;
  allow.kind = ActionKind::Allow;
  allow.allow = Allowance{AllowPart::Held, "person", std::nullopt, 0.005};
  allow.body = {call};
  allow.span = at(7);
  SkillInstance si;
  si.skill = "feed";
  si.name = "feed";
  si.actions = {allow};
  g.tasks[0].instances.push_back(si);
  return g;
}

TEST(Validator, ClearancesHaveADistanceAndBodies) {
  EXPECT_TRUE(validate(graphWithAllow()).empty());
  ConstraintGraph g = graphWithAllow();
  g.clearances[0].distance = -0.01;
  g.clearances[0].bodies.clear();
  g.clearances.push_back(g.clearances[0]);
  auto p = validate(g);
  EXPECT_TRUE(mentions(p, "clearance person: distance -0.01 is not a finite number >= 0"));
  EXPECT_TRUE(mentions(p, "clearance person names no body"));
  EXPECT_TRUE(mentions(p, "clearance person is declared twice"));
  g = graphWithAllow();
  g.clearances[0].distance = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(mentions(validate(g), "is not a finite number"));
}

TEST(Validator, AnAllowHasOneTargetADeclaredClearanceAndABody) {
  ConstraintGraph g = graphWithAllow();
  Action& allow = g.tasks[0].instances[0].actions[0];
  Expr geom;
  geom.op = Op::Str;
  geom.text = "table_top";
  geom.type = {TypeKind::Text, "text"};
  allow.allow->target = geom;
  EXPECT_TRUE(mentions(validate(g), "task main, feed: an allowance needs exactly one of a clearance and a target"));
  allow.allow->clearance.clear();
  EXPECT_TRUE(validate(g).empty());
  allow.allow->target.reset();
  EXPECT_TRUE(mentions(validate(g), "exactly one of a clearance and a target"));
  allow.allow->clearance = "pets";
  EXPECT_TRUE(mentions(validate(g), "names the undeclared clearance pets"));
  g = graphWithAllow();
  g.tasks[0].instances[0].actions[0].body.clear();
  EXPECT_TRUE(mentions(validate(g), "an allow action covers no action"));
  g = graphWithAllow();
  g.tasks[0].instances[0].actions[0].allow->separation = std::nan("");
  EXPECT_TRUE(mentions(validate(g), "separation is not finite"));
  g = graphWithAllow();
  g.tasks[0].instances[0].actions[0].allow.reset();
  EXPECT_TRUE(mentions(validate(g), "an allow action has no allowance"));
  g = graphWithAllow();
  g.tasks[0].instances[0].actions[0].body[0].allow = Allowance{};
  EXPECT_TRUE(mentions(validate(g), "a call action has an allowance"));
}

}  // namespace
}  // namespace cbtl::ir
