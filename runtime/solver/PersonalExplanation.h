// PersonalExplanation.h — what the personalized constraints of a CSP say about one assignment: per instance,
// P(holds) against the generator's `accept`, the entropy exploration sees, whether the CSP contained it, and for
// a text factor the subject, the context it was judged in and theta (what the model has learned, as text).
//
// For `cbtl solve --explain` and the REPL's explain: computed from scratch with a fresh PersonalEvaluator, so it
// is the same answer the solver's own evaluation gives, without touching the solver's caches.
#pragma once

#include "runtime/solver/Csp.h"

#include <string>
#include <vector>

namespace cbtl::solver {

struct TextFactorExplanation {
  std::string factor;   // the factor's label
  std::string subject;  // the subject's value at the assignment
  std::string context;  // the context it was judged in ("" when the factor names none)
  std::string theta;    // the model's theta text
};

struct InstanceExplanation {
  std::string name;     // "dipPreferred(acquireBite.dip)"
  std::string key;      // the model key ("" for a generator without `per`)
  bool inCsp = false;   // the CSP constrained it (PersonalMode::Include, or an `explore accepted` generator)
  bool applies = true;  // false: its guard is false at the assignment
  // false: in a staged plan, the state the instance is judged in (its skill's start) is not reached for this
  // assignment (an earlier skill's effect is undefined); then nothing below is its verdict. The re-check
  // (Recheck.h) judges every instance in the same state, so the two always agree.
  bool reached = true;
  double probability = 1;    // P(holds), the reading the constraint thresholds
  double accept = 0.5;       // the generator's `accept`
  bool holds = true;         // probability >= accept (with the evaluator's tolerance), or it does not apply
  double entropyBits = 0;    // Bernoulli entropy of the posterior reading
  std::size_t evidence = 0;  // labelled examples its factors hold for its key: 0 = the prior speaks, nothing learned
  std::vector<TextFactorExplanation> text;
};

// Every personalized instance of `csp`'s task, in the task's instance order, at `assignment`.
std::vector<InstanceExplanation> explainPersonal(const Csp& csp, const std::vector<double>& assignment);

}  // namespace cbtl::solver
