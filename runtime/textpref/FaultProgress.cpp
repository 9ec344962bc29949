#include "runtime/textpref/FaultProgress.h"

#include <fmt/core.h>

namespace cbtl::textpref {

FaultProgress::FaultProgress(Sink sink, std::chrono::milliseconds interval, Clock now)
    : sink_(std::move(sink)), interval_(interval), now_(std::move(now)) {
  if (!now_) now_ = [] { return std::chrono::steady_clock::now(); };
}

void FaultProgress::attemptFailed(const std::string& server, const std::string& what, std::optional<long> waitMs) {
  std::string line;
  {
    std::lock_guard lock(mutex_);
    ++failures_;
    if (waitMs) {
      ++retries_;
      waitedMs_ += *waitMs;
    }
    const auto now = now_();
    if (lastLine_ && now - *lastLine_ < interval_) return;
    lastLine_ = now;
    const std::string next =
        waitMs ? fmt::format("retrying in {:.1f} s", *waitMs / 1000.0) : std::string("giving this request up");
    line = fmt::format("language model: {} {}; {} ({} failed attempt{} so far, {} retr{}, {:.1f} s of waits)", server,
                       what, next, failures_, failures_ == 1 ? "" : "s", retries_, retries_ == 1 ? "y" : "ies",
                       waitedMs_ / 1000.0);
  }
  if (sink_) sink_(line);
}

void FaultProgress::notice(const std::string& line) {
  {
    std::lock_guard lock(mutex_);
    lastLine_ = now_();
  }
  if (sink_) sink_(line);
}

}  // namespace cbtl::textpref
