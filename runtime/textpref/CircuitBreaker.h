// CircuitBreaker.h — stops calling a language-model server that keeps failing at the transport level, so that a
// dead or silent server costs a run a bounded time instead of hours of timeouts.
//
// The breaker counts consecutive transport failures: requests that, after all their retries, ended in a
// Transport or Timeout error (the server never answered). Any HTTP answer, even an error status, resets the
// count. When the count reaches `threshold` the breaker opens and stays open for the rest of the run (the
// lifetime of the object; there is no half-open probing): ChatClient then answers every request that the cache
// cannot with a CircuitOpen error, without touching the network, and callers fall back (counted, FaultStats.h).
// `onOpen` is called exactly once, when the breaker opens, with a one-line notice for stderr.
// threshold 0 disables the breaker (it never opens). Thread-safe.
// Worst-case time spent on a silent server: threshold x attempts x (request timeout + backoff).
#pragma once

#include "runtime/textpref/Result.h"

#include <functional>
#include <mutex>
#include <string>

namespace cbtl::textpref {

class CircuitBreaker {
 public:
  using Notice = std::function<void(const std::string&)>;

  explicit CircuitBreaker(int threshold, Notice onOpen = {});

  int threshold() const { return threshold_; }
  bool isOpen() const;
  // The description of the failure that opened the breaker ("" while closed).
  std::string reason() const;

  // A request failed with `error`; only Transport and Timeout count, other kinds mean the server answered.
  void recordFailure(const Error& error);
  // The server answered (any HTTP status).
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
