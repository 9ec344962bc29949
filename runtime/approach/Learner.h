// Learner.h — applies the generators' learning rules to the user's feedback events.
//
// For every rule whose event matches, the event's arguments are laid out in the rule's frame, the rule's
// `if` condition is checked, and each label is added to its factor's data under the model key the rule's
// binders give (the same key the constraint instances compute from their variables). Malformed events
// (wrong arity or kinds) are reported, never applied.
#pragma once

#include "DomainSimulator.h"
#include "Program.h"
#include "UserModel.h"

#include <string>
#include <vector>

namespace cbtl::approach {

struct LearnReport {
  std::size_t labels = 0;                 // labelled examples added
  std::vector<std::string> problems;      // events that did not fit their declaration
};

class Learner {
 public:
  // Throws rt::RuntimeError when a rule does not bind a `per` key of its generator.
  explicit Learner(const rt::Program& program);
  LearnReport learn(const std::vector<sim::FeedbackEvent>& events, model::UserModel& user) const;

 private:
  const rt::Program& program_;
  // Per generator, per rule, per `per` key: the binder index giving that key.
  std::vector<std::vector<std::vector<std::size_t>>> keyBinders_;
};

}  // namespace cbtl::approach
