// Prompt rendering and the free-text feedback lexicon.
#include "runtime/textpref/FeedbackText.h"
#include "runtime/textpref/Prompts.h"

#include <gtest/gtest.h>

namespace cbtl::textpref {
namespace {

TEST(Prompts, ConstraintPromptCarriesItemThetaAndTheScaleInstruction) {
  const auto t = *builtinPrompts("userEnjoysBook");
  const Item book{"Cosmos", {{"author", {"Carl Sagan"}}, {"genre", {"nonfiction", "science"}}}};
  const std::string digits = renderConstraintPrompt(t, book, {}, "Likes {feedback} astronomy", RatingScale::Digits);
  EXPECT_NE(digits.find("Cosmos (author: Carl Sagan; genre: nonfiction, science)"), std::string::npos);
  EXPECT_NE(digits.find("Likes {feedback} astronomy"), std::string::npos);  // substituted text is not rescanned
  EXPECT_NE(digits.find("from 0 to 10"), std::string::npos);
  const std::string options = renderConstraintPrompt(t, book, {}, "x", RatingScale::NumberedOptions);
  EXPECT_NE(options.find("1. 0\n"), std::string::npos);
  EXPECT_NE(options.find("11. 10\n"), std::string::npos);
  EXPECT_NE(options.find("option number"), std::string::npos);
}

TEST(Prompts, DipPromptShowsTheFood) {
  const auto t = *builtinPrompts("dipPreferred");
  const Context meal{{{"food", {"french fries"}}}};
  const std::string text = renderConstraintPrompt(t, Item{"ketchup", {}}, meal, "Unknown", RatingScale::Digits);
  EXPECT_NE(text.find("food: french fries"), std::string::npos);
  EXPECT_NE(text.find("ketchup"), std::string::npos);
}

TEST(Prompts, LearningPromptListsEveryRecordInOrder) {
  const auto t = *builtinPrompts("userEnjoysBook");
  std::vector<FeedbackRecord> history{{Item{"Cosmos", {}}, {}, "Loved it", true},
                                      {Item{"Moby Dick", {}}, {}, "", false}};
  const std::string text = renderLearningPrompt(t, "Unknown", history);
  const auto first = text.find("1. Cosmos -> \"Loved it\"");
  const auto second = text.find("2. Moby Dick -> the user did not like it");
  ASSERT_NE(first, std::string::npos);
  ASSERT_NE(second, std::string::npos);
  EXPECT_LT(first, second);
  EXPECT_NE(text.find("Possible summaries"), std::string::npos);
}

TEST(Prompts, EveryBuiltinExists) {
  for (const auto& name : builtinPromptNames()) {
    const auto t = builtinPrompts(name);
    ASSERT_TRUE(t.has_value()) << name;
    EXPECT_NE(t->constraint.find("{item}"), std::string::npos) << name;
    EXPECT_NE(t->constraint.find("{theta}"), std::string::npos) << name;
    EXPECT_NE(t->learning.find("{feedback}"), std::string::npos) << name;
  }
  EXPECT_FALSE(builtinPrompts("noSuchConstraint").has_value());
}

TEST(FeedbackText, ReadsPolarityWithNegation) {
  EXPECT_EQ(classifyFeedbackText("Thank you, I really enjoyed that!"), true);
  EXPECT_EQ(classifyFeedbackText("Thanks, but I did not enjoy that one."), false);
  EXPECT_EQ(classifyFeedbackText("I hated it"), false);
  EXPECT_EQ(classifyFeedbackText("not bad at all"), true);
  EXPECT_EQ(classifyFeedbackText("I don't like romance"), false);
  EXPECT_EQ(classifyFeedbackText("Boring."), false);
  EXPECT_EQ(classifyFeedbackText("thanks"), true);
  EXPECT_FALSE(classifyFeedbackText("The cover is blue.").has_value());
}

}  // namespace
}  // namespace cbtl::textpref
