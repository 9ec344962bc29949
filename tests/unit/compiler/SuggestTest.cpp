// "Did you mean" suggestions: edit distance (optimal string alignment) and the closeness threshold.
#include "compiler/util/Suggest.h"

#include <gtest/gtest.h>

namespace cbtl {
namespace {

TEST(EditDistance, CountsEachKindOfEditAsOne) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("temp", "temp"), 0u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
  EXPECT_EQ(editDistance("temp", "tem"), 1u);    // deletion
  EXPECT_EQ(editDistance("temp", "tempo"), 1u);  // insertion
  EXPECT_EQ(editDistance("temp", "tamp"), 1u);   // substitution
  EXPECT_EQ(editDistance("temp", "tmep"), 1u);   // adjacent transposition
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("ab", "ba"), 1u);
  EXPECT_EQ(editDistance("ca", "abc"), 3u);  // OSA: no edit of a transposed pair
}

TEST(EditDistance, IsSymmetric) {
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"require", "requre"}, {"interval", "intervall"}, {"x", "yz"}, {"geometry", "geometri"}}) {
    EXPECT_EQ(editDistance(a, b), editDistance(b, a)) << a << " / " << b;
  }
}

TEST(ClosestMatch, SuggestsOnlyPlausibleTypos) {
  const std::vector<std::string> names = {"temp", "quantity", "real", "interval"};
  EXPECT_EQ(closestMatch("tmep", names), "temp");
  EXPECT_EQ(closestMatch("quantitiy", names), "quantity");
  EXPECT_EQ(closestMatch("reel", names), "real");
  EXPECT_EQ(closestMatch("zzzz", names), "");
  // Up to 4 characters only one edit is allowed.
  EXPECT_EQ(closestMatch("rxxl", names), "");
  // Longer words allow a third of their length.
  EXPECT_EQ(closestMatch("intrvl", names), "interval");
}

TEST(ClosestMatch, NeverSuggestsTheWordItself) {
  EXPECT_EQ(closestMatch("temp", {"temp"}), "");
  EXPECT_EQ(closestMatch("temp", {"temp", "tamp"}), "tamp");
}

TEST(ClosestMatch, TiesGoToTheFirstCandidate) {
  EXPECT_EQ(closestMatch("cat", {"bat", "cot", "car"}), "bat");
  EXPECT_EQ(closestMatch("cat", {"car", "bat"}), "car");
}

}  // namespace
}  // namespace cbtl
