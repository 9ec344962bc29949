#include "runtime/textpref/Prompts.h"

#include <fmt/core.h>

#include <map>

namespace cbtl::textpref {
namespace {

// One pass over the template, so text substituted for one placeholder is never scanned for another.
std::string substitute(const std::string& text, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t open = text.find('{', pos);
    if (open == std::string::npos) break;
    const std::size_t close = text.find('}', open);
    if (close == std::string::npos) break;
    out.append(text, pos, open - pos);
    auto it = values.find(text.substr(open + 1, close - open - 1));
    if (it != values.end()) {
      out += it->second;
      pos = close + 1;
    } else {
      out += '{';
      pos = open + 1;
    }
  }
  out.append(text, pos, std::string::npos);
  return out;
}

}  // namespace

PromptTemplates generatorPrompts(std::string_view question, std::string_view learningInstruction) {
  PromptTemplates t;
  if (question.find("{item}") != std::string_view::npos) {
    t.constraint = std::string(question);
  } else {
    t.constraint = fmt::format(
        "The item: {{item}}. Situation: {{context}}. What we know about the user: {{theta}}. {} "
        "Rate it on a scale from 0 (the user would not want it at all) to 10 (exactly what the user wants).",
        question.empty() ? std::string_view("How much would the user like this item?") : question);
  }
  if (learningInstruction.find("{feedback}") != std::string_view::npos) {
    t.learning = std::string(learningInstruction);
  } else {
    t.learning = fmt::format(
        "You work out what a person prefers from how they reacted. Your description of their preferences so far: "
        "{{theta}}. Their reactions, oldest first:\n{{feedback}}\n{} Write the updated description exactly in this "
        "form: \"Liked so far: [list]. Disliked so far: [list]. Possible summaries of the preferences: "
        "1. [summary] 2. [summary] 3. [summary].\" Reply with that description only and explain nothing.",
        learningInstruction.empty()
            ? std::string_view("Using all of these reactions, describe what the person likes and dislikes.")
            : learningInstruction);
  }
  return t;
}

std::string ratingInstruction(RatingScale scale) {
  if (scale == RatingScale::Digits) return "Reply with a single number from 0 to 10 and nothing else.";
  std::string out = "Choose one of these options:\n";
  for (int r = 0; r <= 10; ++r) out += fmt::format("{}. {}\n", r + 1, r);
  out += "Reply with the option number only (1 to 11) and nothing else.";
  return out;
}

std::string renderConstraintPrompt(const PromptTemplates& templates, const Item& item, const Context& context,
                                   const std::string& theta, RatingScale scale) {
  const std::string text =
      substitute(templates.constraint, {{"item", describeItem(item)},
                                        {"context", context.empty() ? std::string("none") : describeContext(context)},
                                        {"theta", theta}});
  return text + "\n" + ratingInstruction(scale);
}

std::string renderLearningPrompt(const PromptTemplates& templates, const std::string& theta,
                                 std::span<const FeedbackRecord> history) {
  std::string lines;
  int n = 0;
  for (const auto& record : history) lines += fmt::format("{}. {}\n", ++n, describeFeedback(record));
  if (lines.empty()) lines = "(no reactions yet)\n";
  return substitute(templates.learning, {{"theta", theta}, {"feedback", lines}});
}

}  // namespace cbtl::textpref
