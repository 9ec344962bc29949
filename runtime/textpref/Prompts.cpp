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

std::string learningTemplate(std::string_view topic, std::string_view things) {
  return fmt::format(
      "You work out what a person prefers about {0} from how they reacted. Your description of their "
      "preferences so far: {{theta}}. Their reactions, oldest first:\n{{feedback}}\nUsing all of these "
      "reactions, write an updated description of their preferences about {0}, exactly in this form: "
      "\"Liked {1} so far: [list]. Disliked {1} so far: [list]. Possible summaries of the preferences: "
      "1. [summary] 2. [summary] 3. [summary].\" Reply with that description only and explain nothing.",
      topic, things);
}

}  // namespace

std::optional<PromptTemplates> builtinPrompts(std::string_view constraintName) {
  PromptTemplates t;
  if (constraintName == "userEnjoysBook") {
    t.constraint =
        "The book: {item}. What we know about the user: {theta}. You will rate how much this user would enjoy "
        "the book. If the user's earlier reactions already mention this book, rate it from that reaction. "
        "On a scale from 0 (the user would hate it) to 10 (the user would love it), how much would the user "
        "enjoy this book?";
    t.learning = learningTemplate("books", "books");
  } else if (constraintName == "dipPreferred") {
    t.constraint =
        "Food on the plate: {context}. Dip offered: {item}. What we know about the user's dip preferences: "
        "{theta}. On a scale from 0 (the user would not want it at all) to 10 (exactly the dip the user "
        "wants), how much would the user want this dip with this food?";
    t.learning = learningTemplate("dipping sauces for each food", "dips");
  } else if (constraintName == "signalPreferred") {
    t.constraint =
        "Ready signal: {item} (how the user tells the feeding robot to bring the bite). Situation: {context}. "
        "What we know about the user's preferences: {theta}. On a scale from 0 (the user would dislike it) to "
        "10 (the user's favourite), how much would the user like to use this ready signal?";
    t.learning = learningTemplate("ready signals for a feeding robot", "signals");
  } else if (constraintName == "verbosityPreferred") {
    t.constraint =
        "Robot speech setting: {item} (whether the feeding robot talks to the user). Situation: {context}. "
        "What we know about the user's preferences: {theta}. On a scale from 0 (the user would dislike it) to "
        "10 (the user's favourite), how much would the user like this setting?";
    t.learning = learningTemplate("how much a feeding robot speaks", "settings");
  } else {
    return std::nullopt;
  }
  return t;
}

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

std::vector<std::string> builtinPromptNames() {
  return {"userEnjoysBook", "dipPreferred", "signalPreferred", "verbosityPreferred"};
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
