// PersonalEvaluator.h — P(holds) of personalized constraint instances under the current user model.
//
// An instance whose guard is false does not apply: it holds, with probability 1 and no entropy. Otherwise
// P = the product of the generator's factors for the instance's model key. The posterior (for entropy) is the
// product of the factors' full posteriors, except for a generator declared `explore accepted`: its exploration is
// confined to what it accepts, and its entropy is that of the same reading (an interval model before its first
// positive accepts everything with P = 1, so it steers nothing there). The factors for a key are looked
// up once and cached until the key's value or the user model changes, so evaluation in the solve loop
// allocates nothing for interval, threshold and table factors.
//
// A text factor is handed its subject as a textpref::Item: item entries and enum members index the Program's
// precomputed ItemDescriptors; a text subject is converted when its value changes, which allocates only then.
// `scale: relative` divides by the best of the values the CSP can choose: when the subject's variable draws from
// an observed set (`var book : Book in pickable`), the members the observation lists; otherwise its whole item
// set or enum. A subject value with no item (an index out of
// range) reads the generator's `fallback`. A factor with a context is asked in the context the instance's
// observation (or variables) give; the context is rendered again only when one of its values changes. The text
// factor caches its own assessments per context (TextFactor.h).
#pragma once

#include "runtime/core/Personalization.h"
#include "runtime/core/Program.h"
#include "runtime/model/UserModel.h"

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cbtl::solver {

struct PersonalValue {
  bool applies = true;
  double probability = 1.0;  // P(holds) that the constraint thresholds (the model's maximum-likelihood reading)
  double posterior = 1.0;    // P(holds) under the full posterior, for the entropy of exploration (Factor.h)
};

class PersonalEvaluator {
 public:
  PersonalEvaluator(const rt::Program& program, const std::vector<rt::PersonalInstance>& instances,
                    const model::UserModel& user);

  PersonalValue evaluate(std::uint32_t instance, const rt::EvalContext& ctx);

  // The model key of an instance for the current assignment ("seasoning|salt").
  std::string key(std::uint32_t instance, const rt::EvalContext& ctx) const;

  // holds <=> ln P >= ln(accept) - 1e-3 (the reference's tolerance), or the instance does not apply.
  bool holds(std::uint32_t instance, const PersonalValue& v) const;

 private:
  // Where a text factor's subject items come from, per instance and factor.
  struct TextSubject {
    const std::vector<textpref::Item>* domain = nullptr;     // item / enum subjects: the item of every value
    double last = std::numeric_limits<double>::quiet_NaN();  // text subjects: the text id `owned` holds
    textpref::Item owned;
    // Relative scaling over an observed set: the offset of its membership flags in the observation, and the
    // members it lists (built on first use; the observation is fixed for the evaluator's CSP).
    std::optional<std::uint32_t> flags;
    bool availableBuilt = false;
    std::vector<textpref::Item> available;
    // The factor's context (`context: [...]`): its values and the rendered context, rebuilt when a value changes.
    std::vector<double> contextValues;
    model::KeyedContext context;
  };
  struct Cache {
    std::vector<double> keyValues;
    std::uint64_t version = ~std::uint64_t{0};
    const std::vector<model::Factor>* factors = nullptr;
    std::vector<TextSubject> text;  // per factor; empty when the generator has no text factor
  };
  double textProbability(const rt::PersonalInstance& inst, std::size_t factor, const model::Factor& f,
                         TextSubject& subject, double value, const rt::EvalContext& ctx);
  const rt::Program& program_;
  const std::vector<rt::PersonalInstance>& instances_;
  const model::UserModel& user_;
  std::vector<Cache> cache_;
  std::vector<double> acceptThreshold_;
  std::vector<bool> entropyFromAccepted_;  // per instance: its generator explores only where it accepts
};

}  // namespace cbtl::solver
