// FaultStats.h — how often a language-model backend failed, by kind, so that a run says when its ratings fell
// back instead of silently using the generator's `fallback` probability.
//
// FaultStats is the live, thread-safe counter a TextBackend owns and shares with its models: every failed
// rating query (the caller then uses the fallback, TextPreferenceModel.h) and every failed learning request
// (theta kept) is recorded with its ErrorKind; the first error's description (Error::describe(), already
// redacted, Redaction.h) is kept. FaultReport is a plain snapshot of it, plus the circuit breaker's state,
// that a run stores in its result, prints in its summary and writes to llm.json.
#pragma once

#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace cbtl::textpref {

struct FaultReport {
  std::string backend = "offline";                       // "offline" or "openai"
  std::map<std::string, std::int64_t> ratingFallbacks;   // error kind name -> failed rating queries
  std::map<std::string, std::int64_t> learningFailures;  // error kind name -> failed learning requests
  std::string firstError;                                // describe() of the first failure, "" when none
  int breakerThreshold = 0;  // consecutive transport failures that open the breaker; 0 = off
  bool breakerOpen = false;
  std::string breakerReason;  // the failure that opened it, "" while closed
  // The run's retry budget (RetryBudget.h): its limits, what was used, and whether a retry was refused.
  int retryBudget = 0;
  long retryWaitBudgetMs = 0;
  int retriesUsed = 0;
  long retryWaitedMs = 0;
  bool retryBudgetSpent = false;

  std::int64_t ratingFallbackTotal() const;
  std::int64_t learningFailureTotal() const;
  bool any() const { return ratingFallbackTotal() + learningFailureTotal() > 0 || breakerOpen || retryBudgetSpent; }
  // Adds another report's counts (several trials of one command); keeps this report's first error if any.
  void add(const FaultReport& other);
  // {"backend", "rating_fallbacks", "rating_fallbacks_by_kind", "learning_failures",
  //  "learning_failures_by_kind", "first_error" (null when none), "breaker": {"threshold", "open", "reason"},
  //  "retries": {"budget", "used", "wait_budget_ms", "waited_ms", "spent"}}.
  nlohmann::json toJson() const;
  // Human-readable lines (each ending in '\n'), "" when there is nothing to report, e.g.
  //   "language model: 12 ratings fell back to the generator's fallback (no-logprobs 12); first error: ..."
  std::string summary() const;
};

class FaultStats {
 public:
  void recordRatingFailure(const Error& error);
  void recordLearningFailure(const Error& error);
  // Forgets the counts and the first error (a new trial starts); thread-safe.
  void reset();
  // The counts so far; backend and breaker fields are left at their defaults for the owner to fill.
  FaultReport snapshot() const;

 private:
  void record(std::map<std::string, std::int64_t>& counts, const Error& error);

  mutable std::mutex mutex_;
  std::map<std::string, std::int64_t> rating_, learning_;
  std::string firstError_;
};

}  // namespace cbtl::textpref
