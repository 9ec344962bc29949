// SimulatedUser.h — a simulated user with a hidden text preference, the ground truth that experiments and
// tools compare a text-preference model against. The users themselves (their hidden texts, rules and items)
// belong to the domains that simulate them; this is only the mechanism.
//
// A SimulatedUser has a hidden preference text (what an LLM judge reads as theta) and a DescriptorRule (the same
// preference written over item descriptors). Ground truth comes from the backend in use: with a language-model
// judge the user enjoys an item iff the ConstraintPrompt with the hidden text gives P >= 0.5 (the reference
// code's rule); without one, iff the descriptor rule matches. A reaction is a FeedbackRecord with a short phrase
// and the explicit liked flag.
#pragma once

#include "runtime/textpref/Item.h"
#include "runtime/textpref/LlmPreferenceModel.h"
#include "runtime/textpref/Result.h"

#include <memory>
#include <string>
#include <vector>

namespace cbtl::textpref {

// A disjunction of conjunctions of descriptor tests. Each test is "field=value" (matched against the item's
// descriptors, or "item=value" against the name) or "context.field=value" (against the context); comparisons
// ignore case. An empty rule matches nothing.
struct DescriptorRule {
  std::vector<std::vector<std::string>> anyOf;
  bool matches(const Item& item, const Context& context) const;
};

class SimulatedUser {
 public:
  SimulatedUser(std::string name, std::string hiddenPreference, DescriptorRule rule);

  const std::string& name() const { return name_; }
  const std::string& hiddenPreference() const { return hiddenPreference_; }
  const DescriptorRule& rule() const { return rule_; }

  // Judge with a language model from now on (not owned exclusively; may be null to return to the rule).
  void useLanguageModelJudge(std::shared_ptr<LlmPreferenceModel> judge) { judge_ = std::move(judge); }
  bool hasLanguageModelJudge() const { return judge_ != nullptr; }

  // Ground truth: does the user enjoy `item` in `context`? Errors only with a language-model judge.
  Result<bool> enjoys(const Item& item, const Context& context = {}) const;
  // The user's reaction: a thank-you or a complaint, with `liked` set.
  Result<FeedbackRecord> react(const Item& item, const Context& context = {}) const;

 private:
  std::string name_;
  std::string hiddenPreference_;
  DescriptorRule rule_;
  std::shared_ptr<LlmPreferenceModel> judge_;
};

}  // namespace cbtl::textpref
