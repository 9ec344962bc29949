// Learner.h — applies the generators' learning rules to the user's feedback events.
//
// For every rule whose event matches, the event's arguments are laid out in the rule's frame, the rule's
// `if` condition is checked, and each label is added to its factor's data under the model key the rule's
// binders give (the same key the constraint instances compute from their variables). Malformed events
// (wrong arity or kinds) are reported, never applied.
//
// A text factor learns (subject, label) with the subject as the same textpref::Item the evaluator shows it
// (the Program's ItemDescriptors; a text subject becomes an item named by the text), in the factor's context
// evaluated over the rule's frame and the step's observation (the situation the user reacted in). A text model
// that cannot
// rewrite theta (a language-model server that fails) keeps the record and its old theta; that is a model error,
// reported apart from malformed events because the feedback itself was fine.
#pragma once

#include "runtime/core/Program.h"
#include "runtime/model/UserModel.h"
#include "runtime/sim/DomainSimulator.h"

#include <string>
#include <vector>

namespace cbtl::approach {

// The world a step's feedback is about: the solution the robot acted on and the observation its CSP was
// solved against. Rules read them through their features (a rule may measure a chosen point from an observed
// pose). Missing or short vectors read as zeros, never past their end.
struct StepWorld {
  std::vector<double> assignment;
  std::vector<double> observation;
};

struct LearnReport {
  std::size_t labels = 0;                // labelled examples added
  std::vector<std::string> problems;     // events that did not fit their declaration
  std::vector<std::string> modelErrors;  // text models that kept their old theta (the record was kept)
};

class Learner {
 public:
  // Throws rt::RuntimeError when a rule does not bind a `per` key of its generator.
  explicit Learner(const rt::Program& program);
  LearnReport learn(const std::vector<sim::FeedbackEvent>& events, model::UserModel& user,
                    const StepWorld& world = {}) const;

 private:
  const rt::Program& program_;
  // Per generator, per rule, per `per` key: the binder index giving that key.
  std::vector<std::vector<std::vector<std::size_t>>> keyBinders_;
};

}  // namespace cbtl::approach
