// PersonalEvaluator.h — P(holds) of personalized constraint instances under the current user model.
//
// An instance whose guard is false does not apply: it holds, with probability 1 and no entropy. Otherwise
// P = the product of the generator's factors for the instance's model key. The factors for a key are looked
// up once and cached until the key's value or the user model changes, so evaluation in the solve loop
// allocates nothing.
#pragma once

#include "Personalization.h"
#include "Program.h"
#include "UserModel.h"

#include <string>
#include <vector>

namespace cbtl::solver {

struct PersonalValue {
  bool applies = true;
  double probability = 1.0;
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
  struct Cache {
    std::vector<double> keyValues;
    std::uint64_t version = ~std::uint64_t{0};
    const std::vector<model::Factor>* factors = nullptr;
  };
  const rt::Program& program_;
  const std::vector<rt::PersonalInstance>& instances_;
  const model::UserModel& user_;
  std::vector<Cache> cache_;
  std::vector<double> acceptThreshold_;
};

}  // namespace cbtl::solver
