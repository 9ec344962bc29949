// RetryBudget.h — the retries a whole run may spend on a failing language-model server, shared by every request
// of that run, so that a server that keeps answering 5xx or 429 cannot multiply a run's length by the number
// of requests.
//
// Two limits, both counts of what the client asks for rather than measured time, so that a run with the same
// seed against the same server counts the same: `retries` (retries, first attempts not included) and `waitMs`
// (the sum of the waits requested before retries: backoff and Retry-After, each already capped by
// RetryPolicy::maxRetryAfterMs). A retry is granted only while both remain: take(w) needs one retry and w ms.
// The first refusal spends the budget for good: from then on every take() is refused until reset() (a new run),
// so a run with a spent budget tries each request once. Requests are still made (a server that recovers still
// rates); a server that keeps failing opens the circuit breaker (CircuitBreaker.h) after its threshold.
// `onSpent` is called once per run, when the budget is first refused, with a one-line notice. Thread-safe.
#pragma once

#include <functional>
#include <mutex>
#include <string>

namespace cbtl::textpref {

struct RetryBudgetLimits {
  int retries = 100;     // retries per run, >= 0 (0: no request is ever retried)
  long waitMs = 300000;  // total requested wait before retries per run, milliseconds, >= 0
};

enum class RetryGrant {
  Granted,       // retry, after the requested wait (both were taken from the budget)
  RetriesSpent,  // refused: no retries left (or the budget was spent earlier in the run)
  WaitSpent,     // refused: the wait would exceed what remains of the wait budget
};

// What a run spent; `spent` once a retry was refused.
struct RetryBudgetUse {
  int retries = 0;
  long waitedMs = 0;
  bool spent = false;
};

class RetryBudget {
 public:
  using Notice = std::function<void(const std::string&)>;

  explicit RetryBudget(RetryBudgetLimits limits, Notice onSpent = {});

  const RetryBudgetLimits& limits() const { return limits_; }
  // Asks for one retry after waiting `waitMs` (clamped to >= 0).
  RetryGrant take(long waitMs);
  RetryBudgetUse used() const;
  // A new run starts: everything is available again.
  void reset();

 private:
  const RetryBudgetLimits limits_;
  Notice onSpent_;
  mutable std::mutex mutex_;
  RetryBudgetUse used_;
};

}  // namespace cbtl::textpref
