#include "runtime/textpref/RetryBudget.h"

#include <fmt/core.h>

#include <algorithm>

namespace cbtl::textpref {

RetryBudget::RetryBudget(RetryBudgetLimits limits, Notice onSpent)
    : limits_{std::max(0, limits.retries), std::max(0L, limits.waitMs)}, onSpent_(std::move(onSpent)) {}

RetryGrant RetryBudget::take(long waitMs) {
  waitMs = std::max(0L, waitMs);
  RetryGrant grant = RetryGrant::Granted;
  std::string notice;
  {
    std::lock_guard lock(mutex_);
    if (used_.spent || used_.retries >= limits_.retries) {
      grant = RetryGrant::RetriesSpent;
    } else if (waitMs > limits_.waitMs - used_.waitedMs) {
      grant = RetryGrant::WaitSpent;
    } else {
      ++used_.retries;
      used_.waitedMs += waitMs;
      return RetryGrant::Granted;
    }
    if (!used_.spent) {
      used_.spent = true;
      notice = fmt::format(
          "language model: retry budget spent ({} of {} retries, {:.1f} of {:.1f} s of waits used): no request is "
          "retried for the rest of this run",
          used_.retries, limits_.retries, used_.waitedMs / 1000.0, limits_.waitMs / 1000.0);
    }
  }
  if (!notice.empty() && onSpent_) onSpent_(notice);
  return grant;
}

RetryBudgetUse RetryBudget::used() const {
  std::lock_guard lock(mutex_);
  return used_;
}

void RetryBudget::reset() {
  std::lock_guard lock(mutex_);
  used_ = RetryBudgetUse{};
}

}  // namespace cbtl::textpref
