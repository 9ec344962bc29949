#include "runtime/textpref/FaultStats.h"

#include <fmt/core.h>

namespace cbtl::textpref {
namespace {

std::int64_t total(const std::map<std::string, std::int64_t>& counts) {
  std::int64_t n = 0;
  for (const auto& [kind, count] : counts) n += count;
  return n;
}

std::string byKind(const std::map<std::string, std::int64_t>& counts) {
  std::string out;
  for (const auto& [kind, count] : counts) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", kind, count);
  return out;
}

}  // namespace

std::int64_t FaultReport::ratingFallbackTotal() const { return total(ratingFallbacks); }
std::int64_t FaultReport::learningFailureTotal() const { return total(learningFailures); }

void FaultReport::add(const FaultReport& other) {
  for (const auto& [kind, count] : other.ratingFallbacks) ratingFallbacks[kind] += count;
  for (const auto& [kind, count] : other.learningFailures) learningFailures[kind] += count;
  if (firstError.empty()) firstError = other.firstError;
  if (other.breakerOpen && !breakerOpen) {
    breakerOpen = true;
    breakerReason = other.breakerReason;
  }
  breakerThreshold = other.breakerThreshold;
  retryBudget = other.retryBudget;
  retryWaitBudgetMs = other.retryWaitBudgetMs;
  retriesUsed += other.retriesUsed;
  retryWaitedMs += other.retryWaitedMs;
  retryBudgetSpent = retryBudgetSpent || other.retryBudgetSpent;
  backend = other.backend;
}

nlohmann::json FaultReport::toJson() const {
  return nlohmann::json{{"backend", backend},
                        {"rating_fallbacks", ratingFallbackTotal()},
                        {"rating_fallbacks_by_kind", ratingFallbacks},
                        {"learning_failures", learningFailureTotal()},
                        {"learning_failures_by_kind", learningFailures},
                        {"first_error", firstError.empty() ? nlohmann::json(nullptr) : nlohmann::json(firstError)},
                        {"breaker",
                         {{"threshold", breakerThreshold},
                          {"open", breakerOpen},
                          {"reason", breakerReason.empty() ? nlohmann::json(nullptr) : nlohmann::json(breakerReason)}}},
                        {"retries",
                         {{"budget", retryBudget},
                          {"used", retriesUsed},
                          {"wait_budget_ms", retryWaitBudgetMs},
                          {"waited_ms", retryWaitedMs},
                          {"spent", retryBudgetSpent}}}};
}

std::string FaultReport::summary() const {
  std::string out;
  if (const auto n = ratingFallbackTotal(); n > 0)
    out += fmt::format("language model: {} rating{} fell back to the generator's fallback ({})\n", n, n == 1 ? "" : "s",
                       byKind(ratingFallbacks));
  if (const auto n = learningFailureTotal(); n > 0)
    out += fmt::format("language model: {} learning request{} failed, theta kept ({})\n", n, n == 1 ? "" : "s",
                       byKind(learningFailures));
  if (!firstError.empty()) out += fmt::format("language model: first error: {}\n", firstError);
  if (breakerOpen)
    out += fmt::format(
        "language model: circuit breaker open after {} consecutive server failures: the server "
        "was not called again ({})\n",
        breakerThreshold, breakerReason);
  if (retryBudgetSpent)
    out += fmt::format(
        "language model: retry budget spent ({} retries, {:.1f} s of waits): later failed requests were not "
        "retried\n",
        retriesUsed, retryWaitedMs / 1000.0);
  return out;
}

void FaultStats::record(std::map<std::string, std::int64_t>& counts, const Error& error) {
  std::lock_guard lock(mutex_);
  ++counts[errorKindName(error.kind)];
  if (firstError_.empty()) firstError_ = error.describe();
}

void FaultStats::recordRatingFailure(const Error& error) { record(rating_, error); }
void FaultStats::recordLearningFailure(const Error& error) { record(learning_, error); }

void FaultStats::reset() {
  std::lock_guard lock(mutex_);
  rating_.clear();
  learning_.clear();
  firstError_.clear();
}

FaultReport FaultStats::snapshot() const {
  std::lock_guard lock(mutex_);
  FaultReport r;
  r.ratingFallbacks = rating_;
  r.learningFailures = learning_;
  r.firstError = firstError_;
  return r;
}

}  // namespace cbtl::textpref
