#include "runtime/textpref/RetryPolicy.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <thread>

namespace cbtl::textpref {

bool isQuotaError(long status, const std::string& body) {
  if (status != 429) return false;
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("error") || !j["error"].is_object()) return false;
  const auto& e = j["error"];
  for (const char* field : {"code", "type"})
    if (e.contains(field) && e[field].is_string() && e[field].get<std::string>() == "insufficient_quota") return true;
  return false;
}

RetryDecision classifyResponse(const HttpResponse& response) {
  const long s = response.status;
  if (s >= 200 && s < 300) return RetryDecision::Done;
  if (isQuotaError(s, response.body)) return RetryDecision::Quota;
  const std::string hint = response.header("x-should-retry");
  if (hint == "true") return RetryDecision::Retry;
  if (hint == "false") return RetryDecision::Fail;
  if (s == 408 || s == 409 || s == 429 || (s >= 500 && s < 600)) return RetryDecision::Retry;
  return RetryDecision::Fail;
}

namespace {
std::optional<double> parseNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value) || value < 0.0) return std::nullopt;
  return value;
}
}  // namespace

std::optional<long> retryAfterMs(const HttpResponse& response, const RetryPolicy& policy) {
  std::optional<double> ms;
  if (auto v = parseNumber(response.header("retry-after-ms"))) {
    ms = *v;
  } else if (auto s = parseNumber(response.header("retry-after"))) {
    ms = *s * 1000.0;
  }
  if (!ms) return std::nullopt;
  return std::clamp(static_cast<long>(std::llround(*ms)), 0L, policy.maxRetryAfterMs);
}

long backoffDelayMs(int retryIndex, const RetryPolicy& policy, std::mt19937_64& rng) {
  const int k = std::clamp(retryIndex, 0, 30);
  const double raw =
      std::min(static_cast<double>(policy.baseDelayMs) * std::ldexp(1.0, k), static_cast<double>(policy.maxDelayMs));
  std::uniform_real_distribution<double> jitter(std::clamp(policy.jitterMin, 0.0, 1.0), 1.0);
  return static_cast<long>(std::llround(raw * jitter(rng)));
}

SleepFunction realSleep() {
  return [](std::chrono::milliseconds d) { std::this_thread::sleep_for(d); };
}

}  // namespace cbtl::textpref
