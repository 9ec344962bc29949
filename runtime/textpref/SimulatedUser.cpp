#include "runtime/textpref/SimulatedUser.h"

#include <algorithm>
#include <cctype>

namespace cbtl::textpref {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool fieldHas(const Descriptors& fields, const std::string& field, const std::string& value) {
  for (const auto& [key, values] : fields) {
    if (lower(key) != field) continue;
    for (const auto& v : values)
      if (lower(v) == value) return true;
  }
  return false;
}

bool testHolds(const std::string& test, const Item& item, const Context& context) {
  const auto eq = test.find('=');
  if (eq == std::string::npos) return false;
  const std::string field = lower(test.substr(0, eq));
  const std::string value = lower(test.substr(eq + 1));
  if (field == "item") return lower(item.name) == value;
  if (field.rfind("context.", 0) == 0) return fieldHas(context.fields, field.substr(8), value);
  return fieldHas(item.descriptors, field, value);
}

}  // namespace

bool DescriptorRule::matches(const Item& item, const Context& context) const {
  for (const auto& all : anyOf) {
    if (all.empty()) continue;
    if (std::all_of(all.begin(), all.end(), [&](const std::string& t) { return testHolds(t, item, context); }))
      return true;
  }
  return false;
}

SimulatedUser::SimulatedUser(std::string name, std::string hiddenPreference, DescriptorRule rule)
    : name_(std::move(name)), hiddenPreference_(std::move(hiddenPreference)), rule_(std::move(rule)) {}

Result<bool> SimulatedUser::enjoys(const Item& item, const Context& context) const {
  if (!judge_) return rule_.matches(item, context);
  auto assessment = judge_->assessWithTheta(item, context, hiddenPreference_);
  if (!assessment) return assessment.error();
  return assessment.value().probability >= 0.5 - 1e-6;
}

Result<FeedbackRecord> SimulatedUser::react(const Item& item, const Context& context) const {
  auto liked = enjoys(item, context);
  if (!liked) return liked.error();
  FeedbackRecord record;
  record.item = item;
  record.context = context;
  record.liked = liked.value();
  record.text = liked.value() ? "Thank you, I really enjoyed that!" : "Thanks, but I did not enjoy that one.";
  return record;
}

}  // namespace cbtl::textpref
