#include "app/LoadedProgram.h"
#include "app/repl/ValueSyntax.h"

#include <gtest/gtest.h>

using namespace cbtl;
using namespace cbtl::app::repl;

namespace {

sim::Value literal(const std::string& text) {
  SyntaxError error;
  auto v = parseLiteral(text, error);
  EXPECT_TRUE(v.has_value()) << text << ": " << error.message;
  return v.value_or(sim::Value{});
}

SyntaxError literalError(const std::string& text) {
  SyntaxError error;
  EXPECT_FALSE(parseLiteral(text, error).has_value()) << text;
  return error;
}

const app::LoadedProgram& cooking() {
  static auto lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/cooking/cooking.cbtl");
  return *lp;
}

}  // namespace

TEST(ValueSyntax, LiteralsTakeTheKindTheirSpellingSays) {
  EXPECT_EQ(literal(" -1.5e2 ").number, -150);
  EXPECT_EQ(literal("+3").number, 3);
  EXPECT_EQ(literal("true").number, 1);
  EXPECT_EQ(literal("false").kind, sim::Value::Kind::Number);
  EXPECT_EQ(literal("dips.ranch").text, "dips.ranch");
  EXPECT_EQ(literal("\"no \\\"dip\\\"\"").text, "no \"dip\"");
  EXPECT_EQ(literal("(0.3, -0.2, 1e-3)").vector, (std::vector<double>{0.3, -0.2, 0.001}));
  EXPECT_TRUE(literal("()").vector.empty());
  EXPECT_EQ(literal("{ketchup, dips.bbqSauce}").members, (std::vector<std::string>{"ketchup", "dips.bbqSauce"}));
  EXPECT_TRUE(literal("{}").members.empty());
}

TEST(ValueSyntax, ErrorsNameTheColumn) {
  EXPECT_EQ(literalError("(1, 2").column, 5u);
  EXPECT_EQ(literalError("(1, x)").column, 4u);
  EXPECT_EQ(literalError("1.2.3").column, 0u);
  EXPECT_EQ(literalError("ranch 2").column, 6u);
  EXPECT_NE(literalError("\"open").message.find("unterminated"), std::string::npos);
  EXPECT_NE(literalError("").message.find("expected a value"), std::string::npos);
  EXPECT_NE(literalError("1e999").message.find("not a number"), std::string::npos);
}

TEST(ValueSyntax, EventsListTheirArgumentsWithColumns) {
  SyntaxError error;
  auto e = parseEvent("dipAnswer(frenchFries, ketchup, (1, 2))", error);
  ASSERT_TRUE(e.has_value()) << error.message;
  EXPECT_EQ(e->name, "dipAnswer");
  ASSERT_EQ(e->args.size(), 3u);
  EXPECT_EQ(e->argColumns, (std::vector<std::size_t>{10, 23, 32}));
  EXPECT_TRUE(parseEvent("ping()", error).has_value());
  EXPECT_FALSE(parseEvent("dipAnswer frenchFries", error).has_value());
  EXPECT_EQ(error.column, 10u);
  EXPECT_FALSE(parseEvent("ping() extra", error).has_value());
  EXPECT_EQ(error.column, 7u);
}

TEST(ValueSyntax, CoercionChecksTheDeclaredType) {
  const auto& lp = cooking();
  ASSERT_TRUE(lp.ok()) << lp.errors();
  const rt::Program& program = lp.program();
  const rt::ValueType critique{rt::ValueKind::Enum, 1, "TempCritique"};
  std::string error;
  sim::Value v = sim::Value::name("TempCritique.wantHotter");
  ASSERT_TRUE(coerceTo(program, critique, v, error)) << error;
  EXPECT_EQ(v.text, "wantHotter");
  v = sim::Value::name("tooHot");
  EXPECT_FALSE(coerceTo(program, critique, v, error));
  EXPECT_EQ(error, "'tooHot' is not a TempCritique (tempGood, wantHotter, wantColder)");
  v = sim::Value::num(3.5);
  EXPECT_FALSE(coerceTo(program, rt::ValueType{rt::ValueKind::Int, 1, ""}, v, error));
  v = sim::Value::num(1);
  EXPECT_TRUE(coerceTo(program, rt::ValueType{rt::ValueKind::Bool, 1, ""}, v, error));
  v = sim::Value::num(2);
  EXPECT_FALSE(coerceTo(program, rt::ValueType{rt::ValueKind::Bool, 1, ""}, v, error));
  v = sim::Value::vec({1, 2, 3});
  EXPECT_FALSE(coerceTo(program, rt::ValueType{rt::ValueKind::Vec, 2, ""}, v, error));
  EXPECT_EQ(error, "expected 2 numbers for a vec<2> (2 numbers in parentheses), not 3");
  v = sim::Value::name("salt");
  EXPECT_FALSE(coerceTo(program, rt::ValueType{rt::ValueKind::Real, 1, ""}, v, error));
  EXPECT_EQ(error, "expected a real number");
}
