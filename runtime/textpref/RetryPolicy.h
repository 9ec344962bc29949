// RetryPolicy.h — which failed requests are retried, and how long to wait before the next attempt.
//
// Retried: HTTP 408, 409, 429 (except quota errors), every 5xx, and transport failures (connection refused or
// reset, timeouts) when `retryTransportErrors` is set. A response header `x-should-retry: true|false` overrides
// the status rule. Never retried: 429 whose error code is `insufficient_quota` (billing; waiting cannot help),
// and every other 4xx.
// Waits: `retry-after-ms` (milliseconds) first, then `Retry-After` as delta-seconds (decimals allowed), clamped
// to [0, maxRetryAfterMs] (10 s by default: a server asking for 30 s is retried after 10 s, and a run's total
// wait is bounded by its retry budget, RetryBudget.h); an HTTP-date Retry-After is ignored. Without a usable header the
// wait is min(baseDelayMs * 2^k, maxDelayMs) * u for the k-th retry (k = 0, 1, ...), u uniform in [jitterMin, 1] from
// the caller's seeded RNG. The number of attempts is bounded by maxAttempts (first attempt included): budgets are
// counts, never wall-clock time. Sleeping goes through an injectable SleepFunction so tests never wait.
#pragma once

#include "runtime/textpref/HttpClient.h"

#include <chrono>
#include <functional>
#include <optional>
#include <random>
#include <string>

namespace cbtl::textpref {

struct RetryPolicy {
  int maxAttempts = 5;  // >= 1; 1 means no retries
  long baseDelayMs = 500;
  long maxDelayMs = 8000;
  double jitterMin = 0.75;       // in [0, 1]
  long maxRetryAfterMs = 10000;  // server-requested waits are clamped to this
  bool retryTransportErrors = true;
};

enum class RetryDecision { Done, Retry, Fail, Quota };

// True when `status` is 429 and the body's error.code (or error.type) is "insufficient_quota".
bool isQuotaError(long status, const std::string& body);

// What to do after an HTTP response: Done for 2xx, Quota for quota errors, Retry or Fail otherwise.
RetryDecision classifyResponse(const HttpResponse& response);

// The server-requested wait in milliseconds, if the response carries a usable retry-after-ms or Retry-After.
std::optional<long> retryAfterMs(const HttpResponse& response, const RetryPolicy& policy);

// The capped exponential backoff with jitter for the k-th retry (k >= 0).
long backoffDelayMs(int retryIndex, const RetryPolicy& policy, std::mt19937_64& rng);

using SleepFunction = std::function<void(std::chrono::milliseconds)>;

// std::this_thread::sleep_for.
SleepFunction realSleep();

}  // namespace cbtl::textpref
