// The JSON reader's errors: each kind, with the JSON Pointer of the offending field. The documents are the
// printer's output for a small graph, edited one field at a time.
#include "ir/GraphJsonReader.h"
#include "ir/GraphPrinter.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cbtl::ir {
namespace {

using nlohmann::json;

Expr typed(Op op, TypeKind kind, const char* name) {
  Expr e;
  e.op = op;
  e.type = {kind, name};
  return e;
}
Expr num(double v) {
  Expr e = typed(Op::Num, TypeKind::Real, "real");
  e.number = v;
  return e;
}
Expr var(VarId id) {
  Expr e = typed(Op::Var, TypeKind::Real, "real");
  e.id = id;
  return e;
}

ConstraintGraph smallGraph() {
  ConstraintGraph g;
  g.domain = "test";
  Variable x;
  x.name = "x";
  x.type = {TypeKind::Real, "real"};
  x.domain.bounds.push_back({num(0), num(1)});
  x.scope = "global";
  x.span = {"t.cbtl", 2, 1, 2, 20};
  g.variables.push_back(x);
  Constraint c;
  c.name = "small";
  c.vars = {0};
  c.expr = typed(Op::Lt, TypeKind::Bool, "bool");
  c.expr.children = {var(0), num(0.5)};
  c.scope = "global";
  c.span = {"t.cbtl", 3, 1, 3, 20};
  g.constraints.push_back(c);
  Task t;
  t.name = "main";
  t.vars = {0};
  t.constraints = {0};
  t.implicit = true;
  g.tasks.push_back(t);
  return g;
}

json document() { return json::parse(toJson(smallGraph())); }

GraphReadResult readEdited(const json& doc) { return readGraphJson(doc.dump()); }

TEST(GraphJsonReader, ReadsWhatThePrinterWrites) {
  const GraphReadResult r = readGraphJson(toJson(smallGraph()));
  ASSERT_TRUE(r.ok()) << r.describe("t.json");
  EXPECT_EQ(toJson(r.graph), toJson(smallGraph()));
  EXPECT_EQ(r.graph.constraints[0].expr.children[0].type.kind, TypeKind::Real);
}

TEST(GraphJsonReader, NotJson) {
  const GraphReadResult r = readGraphJson("{\"format\": ");
  EXPECT_EQ(r.outcome, GraphReadOutcome::NotJson);
  EXPECT_EQ(r.pointer, "");
  EXPECT_EQ(r.describe("g.json").rfind("g.json: not valid JSON", 0), 0u) << r.describe("g.json");
}

TEST(GraphJsonReader, WrongFormatTag) {
  json doc = document();
  doc["format"] = "cbtl-profile";
  const GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::WrongFormat);
  EXPECT_EQ(r.pointer, "/format");
  EXPECT_EQ(readGraphJson("[1, 2]").outcome, GraphReadOutcome::WrongFormat);
  doc.erase("format");
  EXPECT_EQ(readEdited(doc).outcome, GraphReadOutcome::WrongFormat);
}

TEST(GraphJsonReader, WrongVersion) {
  json doc = document();
  doc["version"] = 1;
  const GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::WrongVersion);
  EXPECT_EQ(r.describe("g.json"),
            "g.json: /version: version 1 is not supported (this reader reads version 3; emit the graph again with "
            "cbtlc)");
}

TEST(GraphJsonReader, MissingField) {
  json doc = document();
  doc["tasks"][0].erase("name");
  const GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::MissingField);
  EXPECT_EQ(r.describe("g.json"), "g.json: /tasks/0/name: missing field");
  doc = document();
  doc["constraints"][0]["expr"]["children"][1].erase("value");
  EXPECT_EQ(readEdited(doc).pointer, "/constraints/0/expr/children/1/value");
}

TEST(GraphJsonReader, WrongType) {
  json doc = document();
  doc["variables"][0]["span"]["line"] = "two";
  GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::WrongType);
  EXPECT_EQ(r.describe("g.json"), "g.json: /variables/0/span/line: expected an integer, found a string");
  doc = document();
  doc["variables"][0]["span"]["line"] = -3;
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::WrongType);
  EXPECT_EQ(r.pointer, "/variables/0/span/line");
  doc = document();
  doc["tasks"] = json::object();
  EXPECT_EQ(readEdited(doc).pointer, "/tasks");
}

TEST(GraphJsonReader, UnknownName) {
  json doc = document();
  doc["constraints"][0]["expr"]["op"] = "foo";
  GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::UnknownName);
  EXPECT_EQ(r.describe("graph.json"), "graph.json: /constraints/0/expr/op: unknown operation 'foo'");
  doc = document();
  doc["variables"][0]["kind"] = "complex";
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::UnknownName);
  EXPECT_EQ(r.describe("g.json"), "g.json: /variables/0/kind: unknown type kind 'complex'");
}

// smallGraph with a generator on x that CBTL explores only where it accepts.
ConstraintGraph graphWithGenerator() {
  ConstraintGraph g = smallGraph();
  Generator gen;
  gen.name = "lowX";
  gen.params.push_back({"v", {TypeKind::Real, "real"}});
  gen.patterns.push_back({"v", 0, PatternKind::Glob, "x", {"t.cbtl", 4, 1, 4, 10}});
  ModelFactor f;
  f.label = "interval";
  f.kind = FactorKind::Interval;
  f.lo = 0;
  f.hi = 1;
  f.params = {"v"};
  Expr param = typed(Op::Param, TypeKind::Real, "real");
  param.text = "v";
  param.id = 0;
  f.feature = param;
  gen.factors.push_back(f);
  gen.exploreAccepted = true;
  gen.span = {"t.cbtl", 4, 1, 8, 1};
  g.generators.push_back(gen);
  return g;
}

TEST(GraphJsonReader, ExplorationModeRoundTripsAndDefaultsToAnywhere) {
  const GraphReadResult r = readGraphJson(toJson(graphWithGenerator()));
  ASSERT_TRUE(r.ok()) << r.describe("t.json");
  ASSERT_EQ(r.graph.generators.size(), 1u);
  EXPECT_TRUE(r.graph.generators[0].exploreAccepted);
  json doc = json::parse(toJson(graphWithGenerator()));
  EXPECT_EQ(doc["generators"][0]["explore"], "accepted");
  doc["generators"][0].erase("explore");  // a graph written before the clause existed
  GraphReadResult old = readEdited(doc);
  ASSERT_TRUE(old.ok()) << old.describe("t.json");
  EXPECT_FALSE(old.graph.generators[0].exploreAccepted);
  doc["generators"][0]["explore"] = "inside";
  const GraphReadResult bad = readEdited(doc);
  EXPECT_EQ(bad.outcome, GraphReadOutcome::UnknownName);
  EXPECT_EQ(bad.describe("g.json"), "g.json: /generators/0/explore: unknown exploration mode 'inside'");
}

// smallGraph with a clearance and one skill instance whose actions hold two allow blocks, one nested: the first for a
// declared clearance, the inner one for a scene geom given as text.
ConstraintGraph graphWithAllowances() {
  ConstraintGraph g = smallGraph();
  g.clearances.push_back({"person", {"user", "user_head"}, 0.05, {"t.cbtl", 5, 1, 5, 40}});
  Action call;
  call.kind = ActionKind::Call;
  call.name = "say";
  call.span = {"t.cbtl", 7, 5, 7, 20};
  Action inner;
  inner.kind = ActionKind::Allow;
  Expr geom;
  geom.op = Op::Str;
  geom.type = {TypeKind::Text, "text"};
  geom.text = "table_top";
  inner.allow = Allowance{AllowPart::Gripper, "", geom, -0.005};
  inner.body = {call};
  inner.span = {"t.cbtl", 7, 3, 7, 40};
  Action outer;
  outer.kind = ActionKind::Allow;
  outer.allow = Allowance{AllowPart::Held, "person", std::nullopt, 0.005};
  outer.body = {call, inner};
  outer.span = {"t.cbtl", 6, 3, 8, 3};
  SkillInstance si;
  si.skill = "feed";
  si.name = "feed";
  si.actions = {outer};
  si.span = {"t.cbtl", 9, 1, 9, 10};
  g.tasks[0].instances.push_back(si);
  g.skills.push_back("feed");
  return g;
}

TEST(GraphJsonReader, ClearancesAndAllowancesRoundTrip) {
  const GraphReadResult r = readGraphJson(toJson(graphWithAllowances()));
  ASSERT_TRUE(r.ok()) << r.describe("t.json");
  EXPECT_EQ(toJson(r.graph), toJson(graphWithAllowances()));
  ASSERT_EQ(r.graph.clearances.size(), 1u);
  EXPECT_EQ(r.graph.clearances[0].bodies, (std::vector<std::string>{"user", "user_head"}));
  EXPECT_EQ(r.graph.clearances[0].distance, 0.05);
  const Action& outer = r.graph.tasks[0].instances[0].actions[0];
  ASSERT_TRUE(outer.allow.has_value());
  EXPECT_EQ(outer.allow->part, AllowPart::Held);
  EXPECT_EQ(outer.allow->clearance, "person");
  EXPECT_FALSE(outer.allow->target.has_value());
  const Action& inner = outer.body[1];
  ASSERT_TRUE(inner.allow.has_value());
  EXPECT_EQ(inner.allow->part, AllowPart::Gripper);
  ASSERT_TRUE(inner.allow->target.has_value());
  EXPECT_EQ(inner.allow->target->text, "table_top");
  EXPECT_EQ(inner.allow->separation, -0.005);
}

TEST(GraphJsonReader, AllowanceErrorsNameTheirField) {
  const json good = json::parse(toJson(graphWithAllowances()));
  const std::string outer = "/tasks/0/instances/0/actions/0";
  json doc = good;
  doc["tasks"][0]["instances"][0]["actions"][0]["allow"]["part"] = "hand";
  GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::UnknownName);
  EXPECT_EQ(r.describe("g.json"), "g.json: " + outer + "/allow/part: unknown allow part 'hand'");
  doc = good;
  doc["tasks"][0]["instances"][0]["actions"][0].erase("allow");
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::MissingField);
  EXPECT_EQ(r.pointer, outer + "/allow");
  doc = good;
  doc["tasks"][0]["instances"][0]["actions"][0]["allow"]["target"] = doc["constraints"][0]["expr"]["children"][1];
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::Inconsistent);
  EXPECT_EQ(r.pointer, outer + "/allow");
  doc = good;
  doc["tasks"][0]["instances"][0]["actions"][0]["allow"]["clearance"] = "pets";
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::OutOfRange);
  EXPECT_EQ(r.describe("g.json"), "g.json: " + outer +
                                      "/allow/clearance: clearance 'pets' is not declared (not in "
                                      "/clearances)");
  doc = good;
  doc["tasks"][0]["instances"][0]["actions"][0]["body"][0]["allow"] =
      good["tasks"][0]["instances"][0]["actions"][0]["allow"];
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::Inconsistent);
  EXPECT_EQ(r.pointer, outer + "/body/0/allow");
  doc = good;
  doc["clearances"][0]["distance"] = -0.01;
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::Inconsistent);
  EXPECT_EQ(r.pointer, "/clearances/0/distance");
  doc = good;
  doc.erase("clearances");
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::MissingField);
  EXPECT_EQ(r.pointer, "/clearances");
}

TEST(GraphJsonReader, OutOfRange) {
  json doc = document();
  doc["tasks"][0]["constraints"][0] = 3;
  GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::OutOfRange);
  EXPECT_EQ(r.describe("g.json"), "g.json: /tasks/0/constraints/0: constraint 3 does not exist (the graph has 1)");
  doc = document();
  doc["constraints"][0]["expr"]["children"][0]["id"] = 7;
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::OutOfRange);
  EXPECT_EQ(r.pointer, "/constraints/0/expr/children/0/id");
  doc = document();
  doc["constraints"][0]["vars"][0] = 1;
  EXPECT_EQ(readEdited(doc).pointer, "/constraints/0/vars/0");
}

TEST(GraphJsonReader, Inconsistent) {
  json doc = document();
  doc["constraints"][0]["expr"]["children"].erase(1);
  GraphReadResult r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::Inconsistent);
  EXPECT_EQ(r.describe("g.json"), "g.json: /constraints/0/expr/children: '<' takes 2 operands, not 1");
  doc = document();
  doc["variables"][0]["id"] = 4;
  r = readEdited(doc);
  EXPECT_EQ(r.outcome, GraphReadOutcome::Inconsistent);
  EXPECT_EQ(r.pointer, "/variables/0/id");
}

TEST(GraphJsonReader, DeepNestingIsAnErrorNotACrash) {
  json doc = document();
  json e = json::parse(R"({"op": "num", "type": "real", "type_kind": "real", "value": 1})");
  for (int i = 0; i < 1100; ++i) e = json{{"op", "neg"}, {"type", "real"}, {"type_kind", "real"}, {"children", {e}}};
  doc["constraints"][0]["expr"] = e;
  EXPECT_EQ(readEdited(doc).outcome, GraphReadOutcome::Inconsistent);
}

TEST(GraphJsonReader, SniffsTheFormatByItsFirstCharacter) {
  EXPECT_TRUE(looksLikeGraphJson("\xEF\xBB\xBF \n {\"format\": 1}"));
  EXPECT_FALSE(looksLikeGraphJson("// ARGS: emit\ndomain d;"));
  EXPECT_FALSE(looksLikeGraphJson("domain d;"));
  EXPECT_FALSE(looksLikeGraphJson("   "));
}

}  // namespace
}  // namespace cbtl::ir
