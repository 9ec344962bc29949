#include "app/study/AdmissionLimit.h"

#include <algorithm>
#include <cmath>

namespace cbtl::app::study {

AdmissionLimit::AdmissionLimit(AdmissionOptions options) : options_(options), tokens_(options.burst) {}

AdmissionLimit::Decision AdmissionLimit::admit(std::chrono::steady_clock::time_point now, std::int64_t participants) {
  if (options_.total > 0 && participants >= options_.total) return {Verdict::Full, 0};
  if (options_.perMinute <= 0) return {};
  std::lock_guard<std::mutex> lock(mutex_);
  if (started_) {
    const double minutes = std::chrono::duration<double, std::ratio<60>>(now - last_).count();
    tokens_ = std::min(options_.burst, tokens_ + std::max(0.0, minutes) * options_.perMinute);
  }
  started_ = true;
  last_ = now;
  if (tokens_ >= 1) {
    tokens_ -= 1;
    return {};
  }
  const double seconds = (1 - tokens_) / options_.perMinute * 60;
  return {Verdict::TooFast, std::max(1, static_cast<int>(std::ceil(seconds)))};
}

}  // namespace cbtl::app::study
