// Prompt rendering and the free-text feedback lexicon.
#include "runtime/textpref/FeedbackText.h"
#include "runtime/textpref/Prompts.h"

#include <gtest/gtest.h>

namespace cbtl::textpref {
namespace {

TEST(Prompts, ConstraintPromptCarriesItemThetaAndTheScaleInstruction) {
  const auto t = generatorPrompts("How much would the user enjoy this book?", "");
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

TEST(Prompts, ConstraintPromptShowsTheContext) {
  const auto t = generatorPrompts("Would the user enjoy this dip with the food on their plate?", "");
  const Context meal{{{"food", {"french fries"}}}};
  const std::string text = renderConstraintPrompt(t, Item{"ketchup", {}}, meal, "Unknown", RatingScale::Digits);
  EXPECT_NE(text.find("food: french fries"), std::string::npos);
  EXPECT_NE(text.find("ketchup"), std::string::npos);
}

TEST(Prompts, LearningPromptListsEveryRecordInOrder) {
  const auto t = generatorPrompts("", "Describe which books the user likes.");
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

TEST(Prompts, GeneratorWordsAreFramedWithEveryPlaceholder) {
  const auto t = generatorPrompts("Would the user like this?", "Summarize what they like.");
  EXPECT_NE(t.constraint.find("{item}"), std::string::npos);
  EXPECT_NE(t.constraint.find("{theta}"), std::string::npos);
  EXPECT_NE(t.constraint.find("Would the user like this?"), std::string::npos);
  EXPECT_NE(t.learning.find("{feedback}"), std::string::npos);
  EXPECT_NE(t.learning.find("Summarize what they like."), std::string::npos);
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
