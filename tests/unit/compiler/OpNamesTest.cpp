// The name table of the graph's discriminators: every enumerator has one name, and the reader's inverse
// returns it; names the dumps never write are rejected.
#include "ir/OpNames.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace cbtl::ir {
namespace {

// Checks name() and fromName() over the enumerators 0 .. last: names distinct, round trip exact.
template <class E, class FromName>
void expectRoundTrip(E last, FromName fromName) {
  std::set<std::string> seen;
  for (int i = 0; i <= static_cast<int>(last); ++i) {
    const E value = static_cast<E>(i);
    const std::string spelled(name(value));
    EXPECT_NE(spelled, "?") << "enumerator " << i << " has no name";
    EXPECT_TRUE(seen.insert(spelled).second) << "two enumerators are named '" << spelled << "'";
    const auto back = fromName(spelled);
    ASSERT_TRUE(back.has_value()) << spelled;
    EXPECT_EQ(*back, value) << spelled;
  }
}

TEST(OpNames, EveryEnumeratorRoundTrips) {
  expectRoundTrip(Op::Invalid, opFromName);
  expectRoundTrip(TypeKind::Void, typeKindFromName);
  expectRoundTrip(PatternKind::Regex, patternKindFromName);
  expectRoundTrip(FactorKind::Text, factorKindFromName);
  expectRoundTrip(ThresholdDirection::Below, thresholdDirectionFromName);
  expectRoundTrip(TextScale::Relative, textScaleFromName);
  expectRoundTrip(TextRating::Options, textRatingFromName);
  expectRoundTrip(ActionKind::Allow, actionKindFromName);
  expectRoundTrip(AllowPart::Held, allowPartFromName);
  expectRoundTrip(FunctionKind::Feedback, functionKindFromName);
}

TEST(OpNames, TheDumpSpellings) {
  EXPECT_EQ(name(Op::Num), "num");
  EXPECT_EQ(name(Op::EnumSet), "enumset");
  EXPECT_EQ(name(Op::Implies), "=>");
  EXPECT_EQ(name(Op::Le), "<=");
  EXPECT_EQ(name(Op::And), "and");
  EXPECT_EQ(name(TypeKind::SE2), "SE2");
  EXPECT_EQ(name(TypeKind::Conf), "Conf");
  EXPECT_EQ(name(ThresholdDirection::None), "");
  EXPECT_EQ(name(FunctionKind::Feedback), "feedback");
  EXPECT_EQ(name(ActionKind::Allow), "allow");
  EXPECT_EQ(name(AllowPart::Robot), "robot");
  EXPECT_EQ(name(AllowPart::Gripper), "gripper");
  EXPECT_EQ(name(AllowPart::Held), "held");
}

TEST(OpNames, UnknownNamesAreRejected) {
  EXPECT_FALSE(opFromName("").has_value());
  EXPECT_FALSE(opFromName("Num").has_value());  // case-sensitive
  EXPECT_FALSE(opFromName("..").has_value());   // the text dump's infix spelling of range, not its name
  EXPECT_FALSE(opFromName(" num").has_value());
  EXPECT_FALSE(typeKindFromName("se2").has_value());
  EXPECT_FALSE(factorKindFromName("bogus").has_value());
  EXPECT_FALSE(thresholdDirectionFromName("none").has_value());
  EXPECT_FALSE(actionKindFromName("").has_value());
  EXPECT_FALSE(allowPartFromName("hand").has_value());
  EXPECT_FALSE(allowPartFromName("Held").has_value());
}

TEST(OpNames, BinaryOperatorsAreAddThroughIff) {
  EXPECT_TRUE(isBinary(Op::Add));
  EXPECT_TRUE(isBinary(Op::Iff));
  EXPECT_TRUE(isBinary(Op::Lt));
  EXPECT_FALSE(isBinary(Op::Not));
  EXPECT_FALSE(isBinary(Op::Range));
  EXPECT_FALSE(isBinary(Op::In));
}

}  // namespace
}  // namespace cbtl::ir
