// Initiation patterns: glob parsing and matching (captures, literal brackets, no match), regexes.
#include "ir/Pattern.h"

#include <gtest/gtest.h>

namespace cbtl {
namespace {

GlobPattern glob(const std::string& text) {
  std::string error;
  std::size_t at = 0;
  auto g = parseGlob(text, error, at);
  EXPECT_TRUE(g.has_value()) << text << ": " << error;
  return g.value_or(GlobPattern{});
}

bool matches(const std::string& pattern, const std::string& name) {
  std::map<std::string, std::string> b;
  return matchGlob(glob(pattern), name, b);
}

TEST(Glob, StarMatchesAnyRunIncludingEmpty) {
  EXPECT_TRUE(matches("*Conf", "aboveConf"));
  EXPECT_TRUE(matches("*Conf", "Conf"));
  EXPECT_TRUE(matches("*Conf", "acquireBite.robotAbovePlateConf"));
  EXPECT_FALSE(matches("*Conf", "aboveConfig"));
  EXPECT_TRUE(matches("*", ""));
  EXPECT_TRUE(matches("a*b*c", "abc"));
  EXPECT_TRUE(matches("a*b*c", "a-b-b-c"));
}

TEST(Glob, QuestionMarkMatchesExactlyOne) {
  EXPECT_TRUE(matches("slot[?]", "slot[2]"));
  EXPECT_FALSE(matches("slot[?]", "slot[]"));
  EXPECT_FALSE(matches("slot[?]", "slot[12]"));
}

TEST(Glob, BracketsAreLiteral) {
  EXPECT_TRUE(matches("temp[salt]", "temp[salt]"));
  EXPECT_FALSE(matches("temp[salt]", "temps"));
  EXPECT_FALSE(matches("temp[ab]", "tempa"));  // not a character class
  EXPECT_TRUE(matches("*[pepper]", "cook.quantity[pepper]"));
}

TEST(Glob, MatchesTheWholeName) {
  EXPECT_FALSE(matches("meal", "mealPlan"));
  EXPECT_FALSE(matches("meal", "aMeal"));
  EXPECT_TRUE(matches("meal", "meal"));
}

TEST(Glob, CapturesBindTextAndMustAgreeAcrossPatterns) {
  std::map<std::string, std::string> b;
  ASSERT_TRUE(matchGlob(glob("*startTick[{ing}]"), "startTick[salt]", b));
  EXPECT_EQ(b.at("ing"), "salt");
  // The same capture in another pattern must bind the same text.
  EXPECT_TRUE(matchGlob(glob("*quantity[{ing}]"), "quantity[salt]", b));
  std::map<std::string, std::string> before = b;
  EXPECT_FALSE(matchGlob(glob("*quantity[{ing}]"), "quantity[pepper]", b));
  EXPECT_EQ(b, before);  // a failed match leaves the bindings unchanged
}

TEST(Glob, CapturesAreNonEmptyAndListedOnce) {
  const GlobPattern g = glob("{a}.{b}[{a}]");
  ASSERT_EQ(g.captures.size(), 2u);
  EXPECT_EQ(g.captures[0], "a");
  EXPECT_EQ(g.captures[1], "b");
  std::map<std::string, std::string> b;
  EXPECT_TRUE(matchGlob(g, "x.y[x]", b));
  EXPECT_FALSE(matchGlob(g, "x.y[z]", b = {}));
  EXPECT_FALSE(matchGlob(glob("{a}x"), "x", b = {}));  // {a} needs at least one character
}

TEST(Glob, MalformedPatternsSayWhere) {
  std::string error;
  std::size_t at = 99;
  EXPECT_FALSE(parseGlob("ab{oops", error, at).has_value());
  EXPECT_EQ(at, 2u);
  EXPECT_NE(error.find("never closed"), std::string::npos);
  EXPECT_FALSE(parseGlob("x{}", error, at).has_value());
  EXPECT_EQ(at, 1u);
  EXPECT_NE(error.find("needs a name"), std::string::npos);
  EXPECT_FALSE(parseGlob("{1a}", error, at).has_value());
  EXPECT_NE(error.find("not an identifier"), std::string::npos);
  EXPECT_FALSE(parseGlob("a}b", error, at).has_value());
  EXPECT_EQ(at, 1u);
}

TEST(Glob, PathologicalPatternsStopWithinTheBudget) {
  // Many stars against a long non-matching name would take exponential time without the step budget.
  const GlobPattern g = glob("*a*a*a*a*a*a*a*a*a*a*a*b");
  EXPECT_FALSE(matches("*a*a*a*a*a*a*a*a*a*a*a*b", std::string(200, 'a')));
  (void)g;
}

TEST(Regex, CompilesOrExplains) {
  std::string error;
  auto re = compileRegex(".*Conf$", error);
  ASSERT_TRUE(re.has_value());
  EXPECT_TRUE(std::regex_match("aboveConf", *re));
  EXPECT_FALSE(std::regex_match("aboveConfig", *re));
  EXPECT_FALSE(compileRegex("(unclosed", error).has_value());
  EXPECT_FALSE(error.empty());
}

TEST(Regex, MatchingTakesPolynomialTime) {
  // A backtracking matcher needs about 2^40 steps here; the breadth-first one answers at once.
  std::string error;
  auto re = compileRegex("(a*)*b", error);
  ASSERT_TRUE(re.has_value()) << error;
  EXPECT_FALSE(std::regex_match(std::string(40, 'a'), *re));
  EXPECT_FALSE(compileRegex("(a)\\1", error).has_value());  // back-references are refused
}

TEST(Regex, LongOrDeepPatternsAreRefusedBeforeStdRegexSeesThem) {
  std::string error;
  EXPECT_FALSE(
      compileRegex(std::string(kMaxRegexNesting + 1, '(') + "a" + std::string(kMaxRegexNesting + 1, ')'), error));
  EXPECT_NE(error.find("nests groups"), std::string::npos);
  EXPECT_TRUE(compileRegex(std::string(kMaxRegexNesting, '(') + "a" + std::string(kMaxRegexNesting, ')'), error));
  EXPECT_TRUE(compileRegex("[(((((((((((((((((((((((((((((((((((((((((((((((((((((]", error))
      << error;  // literal in a class
  EXPECT_FALSE(compileRegex(std::string(kMaxRegexLength + 1, 'a'), error));
  EXPECT_NE(error.find("longer than"), std::string::npos);
}

TEST(Glob, LongPatternsNeitherOverflowTheStackNorMatchSlowly) {
  // Consecutive stars are one piece, so 60000 of them match like one.
  EXPECT_TRUE(matches(std::string(60000, '*'), "anything"));
  EXPECT_EQ(glob(std::string(100, '*') + "x").pieces.size(), 2u);
  // Past the depth limit a pattern does not match (instead of recursing once per piece).
  std::string many;
  for (int i = 0; i < 5000; ++i) many += "?*";
  EXPECT_FALSE(matches(many, std::string(5000, 'n')));
}

}  // namespace
}  // namespace cbtl
