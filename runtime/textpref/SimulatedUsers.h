// SimulatedUsers.h — the hidden preferences of the Books user and the feeding user, and the items they judge.
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

// The paper's nine standard books, with author, genre and topic descriptors (title is the name).
std::vector<Item> standardBooks();
// The Books user: enjoys only fictional romances and grand nonfiction about the universe (of the nine standard
// books: Cosmos and Pride and Prejudice).
SimulatedUser booksUser();

// Feeding: the dips, ready signals and verbosity settings of the paper's web study, and the five meals' foods as
// contexts ({"food": {name}, "food-type": {...}}).
std::vector<Item> feedingDips();
std::vector<Item> feedingReadySignals();
std::vector<Item> feedingVerbosityLevels();
std::vector<Context> feedingMeals();
// The feeding user's three preferences, one simulated user per personalized constraint.
SimulatedUser feedingDipUser();
SimulatedUser feedingSignalUser();
SimulatedUser feedingVerbosityUser();

}  // namespace cbtl::textpref
