// FaultProgress.h — live lines about a failing language-model server for a person watching a terminal, so that a
// slow or broken server shows up while the run goes on instead of as silence until the end.
//
// The owner creates one only when stderr is a terminal (tools/cbtl/RuntimeSupport.h); without one nothing is
// printed, so piped output and logs stay stable (the circuit breaker's one-line notice is printed either way,
// CircuitBreaker.h). ChatClient reports every failed attempt; the first is printed at once, later ones at most one
// line per `interval` (each line carries the totals, so nothing is lost by the lines skipped). notice() lines (the
// retry budget is spent) are always printed. Time comes from an injectable clock so tests never wait. Thread-safe.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace cbtl::textpref {

class FaultProgress {
 public:
  using Sink = std::function<void(const std::string&)>;  // one line, without '\n'
  using Clock = std::function<std::chrono::steady_clock::time_point()>;

  // A null `now` is std::chrono::steady_clock::now.
  explicit FaultProgress(Sink sink, std::chrono::milliseconds interval = std::chrono::seconds(5), Clock now = {});

  // One attempt at `server` failed with `what` (e.g. "answered HTTP 503", "timeout"); the client waits `waitMs`
  // before retrying, or gives the request up when `waitMs` is nullopt.
  void attemptFailed(const std::string& server, const std::string& what, std::optional<long> waitMs);
  // A line printed whatever the rate limit (and counted as the last line printed).
  void notice(const std::string& line);

 private:
  Sink sink_;
  std::chrono::milliseconds interval_;
  Clock now_;
  std::mutex mutex_;
  long failures_ = 0, retries_ = 0, waitedMs_ = 0;
  std::optional<std::chrono::steady_clock::time_point> lastLine_;
};

}  // namespace cbtl::textpref
