// Prompts.h — ConstraintPrompt and LearningPrompt templates (paper Appendix B), in this project's own words.
//
// A template is plain text with placeholders, replaced verbatim:
//   {item}      the item, as describeItem() writes it
//   {context}   the context, as describeContext() writes it ("none" when empty)
//   {theta}     the current parameter text
//   {feedback}  the whole feedback history, one describeFeedback() line per record, numbered
// Unknown placeholders are left as they are. The constraint template ends with the question; the answer-format
// instruction is appended by ratingInstruction() for the chosen rating scale, so one template serves both scales.
#pragma once

#include "textpref/Item.h"
#include "textpref/RatingReader.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::textpref {

struct PromptTemplates {
  std::string constraint;              // ConstraintPrompt, without the answer-format instruction
  std::string learning;                // LearningPrompt; the reply becomes the new theta
  std::string initialTheta = "Unknown";  // theta before any feedback
};

// The built-in templates: "userEnjoysBook", "dipPreferred", "signalPreferred", "verbosityPreferred".
std::optional<PromptTemplates> builtinPrompts(std::string_view constraintName);
std::vector<std::string> builtinPromptNames();

// The answer-format instruction of a scale: digits ask for one number 0..10; options list "1. 0" .. "11. 10"
// and ask for the option number only.
std::string ratingInstruction(RatingScale scale);

// Template text with the placeholders replaced.
std::string renderConstraintPrompt(const PromptTemplates& templates, const Item& item, const Context& context,
                                   const std::string& theta, RatingScale scale);
std::string renderLearningPrompt(const PromptTemplates& templates, const std::string& theta,
                                 std::span<const FeedbackRecord> history);

}  // namespace cbtl::textpref
