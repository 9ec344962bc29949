// Prompts.h — ConstraintPrompt and LearningPrompt templates (paper Appendix B), in this project's own words.
// The engine holds only the generic framing; a domain's words are the `model text(...)` arguments of its .cbtl
// file (docs/language.md), framed here by generatorPrompts.
//
// A template is plain text with placeholders, replaced verbatim:
//   {item}      the item, as describeItem() writes it
//   {context}   the context, as describeContext() writes it ("none" when empty)
//   {theta}     the current parameter text
//   {feedback}  the whole feedback history, one describeFeedback() line per record, numbered
// Unknown placeholders are left as they are. The constraint template ends with the question; the answer-format
// instruction is appended by ratingInstruction() for the chosen rating scale, so one template serves both scales.
#pragma once

#include "runtime/textpref/Item.h"
#include "runtime/textpref/RatingReader.h"

#include <span>
#include <string>
#include <string_view>

namespace cbtl::textpref {

struct PromptTemplates {
  std::string constraint;                // ConstraintPrompt, without the answer-format instruction
  std::string learning;                  // LearningPrompt; the reply becomes the new theta
  std::string initialTheta = "Unknown";  // theta before any feedback
};

// Templates from a `.cbtl` generator's `model text(subject, prompt: "...", learning: "...")`. The generator's words
// are a question about one subject and an instruction for the summary, without placeholders, so they are framed
// here: the ConstraintPrompt shows the item, the context and theta before the question and asks for a rating from
// 0 to 10; the LearningPrompt shows theta and the reactions before the instruction and asks for a fixed form
// (liked, disliked, three possible summaries). A question that already contains
// "{item}", or an instruction that already contains "{feedback}", is a complete template and is used as written.
// An empty question or instruction (both are optional in the language) gets a generic one.
PromptTemplates generatorPrompts(std::string_view question, std::string_view learningInstruction);

// The answer-format instruction of a scale: digits ask for one number 0..10; options list "1. 0" .. "11. 10"
// and ask for the option number only.
std::string ratingInstruction(RatingScale scale);

// Template text with the placeholders replaced.
std::string renderConstraintPrompt(const PromptTemplates& templates, const Item& item, const Context& context,
                                   const std::string& theta, RatingScale scale);
std::string renderLearningPrompt(const PromptTemplates& templates, const std::string& theta,
                                 std::span<const FeedbackRecord> history);

}  // namespace cbtl::textpref
