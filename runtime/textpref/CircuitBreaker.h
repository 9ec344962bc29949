// CircuitBreaker.h — stops calling a language-model server that keeps failing, so that a dead, silent, broken
// (5xx) or rate-limiting (429) server costs a run a bounded time instead of hours of timeouts and retries.
//
// The breaker counts consecutive server faults: requests that, after all their retries, ended with
//   - no answer: a Transport or Timeout error;
//   - an answer that says the server cannot serve now: HTTP 408, 429 (a rate limit or an exhausted quota) or
//     any 5xx (classifyForBreaker() below).
// Any other outcome resets the count: a 2xx (even one whose body is unusable), and every other 4xx (400, 401,
// 403, 404, 422...), because such an answer says the request or the configuration is wrong, not that the server
// is failing: it is answered at once, costs no retries, and stays visible in the fault counts (FaultStats.h).
// When the count reaches `threshold` the breaker opens and stays open for the rest of the run (the lifetime of
// the object; there is no half-open probing): ChatClient then answers every request that the cache cannot with
// a CircuitOpen error, without touching the network, and callers fall back (counted, FaultStats.h).
// `onOpen` is called exactly once, when the breaker opens, with a one-line notice for stderr.
// threshold 0 disables the breaker (it never opens). Thread-safe.
// Worst-case time before it opens: threshold x attempts x (request timeout + wait before a retry), and the
// run's retry budget (RetryBudget.h) bounds the waits.
#pragma once

#include "runtime/textpref/Result.h"

#include <functional>
#include <mutex>
#include <string>

namespace cbtl::textpref {

// What a finished request (its retries included) tells the breaker.
enum class BreakerOutcome {
  Answered,     // the server answered in a way that says it works (2xx, or a 4xx other than 408/429)
  ServerFault,  // no answer, or 408, 429 or 5xx: counted toward opening the breaker
};

// Transport and Timeout, QuotaExceeded (a 429), and HttpStatus 408, 429 or 500..599 are ServerFault; every other
// error is Answered (the server answered, or the failure was local, e.g. a read-only cache miss).
BreakerOutcome classifyForBreaker(const Error& error);

class CircuitBreaker {
 public:
  using Notice = std::function<void(const std::string&)>;

  explicit CircuitBreaker(int threshold, Notice onOpen = {});

  int threshold() const { return threshold_; }
  bool isOpen() const;
  // The description of the failure that opened the breaker ("" while closed).
  std::string reason() const;

  // A request failed with `error`; counted when classifyForBreaker(error) is ServerFault, else as recordAnswer().
  void recordFailure(const Error& error);
  // The server answered (a usable 2xx, or an error that is not a server fault).
  void recordAnswer();

  // The error returned instead of calling the server while the breaker is open.
  Error openError(const std::string& server) const;

 private:
  const int threshold_;
  Notice onOpen_;
  mutable std::mutex mutex_;
  int consecutive_ = 0;
  bool open_ = false;
  std::string reason_;
};

}  // namespace cbtl::textpref
