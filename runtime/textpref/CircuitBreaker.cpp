#include "runtime/textpref/CircuitBreaker.h"

#include <fmt/core.h>

namespace cbtl::textpref {

BreakerOutcome classifyForBreaker(const Error& error) {
  switch (error.kind) {
    case ErrorKind::Transport:
    case ErrorKind::Timeout:
    case ErrorKind::QuotaExceeded:
      return BreakerOutcome::ServerFault;
    case ErrorKind::HttpStatus: {
      const int s = error.httpStatus;
      return s == 408 || s == 429 || (s >= 500 && s < 600) ? BreakerOutcome::ServerFault : BreakerOutcome::Answered;
    }
    default:
      return BreakerOutcome::Answered;
  }
}

CircuitBreaker::CircuitBreaker(int threshold, Notice onOpen)
    : threshold_(threshold < 0 ? 0 : threshold), onOpen_(std::move(onOpen)) {}

bool CircuitBreaker::isOpen() const {
  std::lock_guard lock(mutex_);
  return open_;
}

std::string CircuitBreaker::reason() const {
  std::lock_guard lock(mutex_);
  return reason_;
}

void CircuitBreaker::recordFailure(const Error& error) {
  if (classifyForBreaker(error) == BreakerOutcome::Answered) {
    recordAnswer();
    return;
  }
  std::string notice;
  {
    std::lock_guard lock(mutex_);
    if (open_ || threshold_ == 0) return;
    if (++consecutive_ < threshold_) return;
    open_ = true;
    reason_ = error.describe();
    notice = fmt::format(
        "language model: circuit breaker open after {} consecutive server failures; the server is not called "
        "again in this run and ratings fall back (last failure: {})",
        consecutive_, reason_);
  }
  if (onOpen_) onOpen_(notice);
}

void CircuitBreaker::recordAnswer() {
  std::lock_guard lock(mutex_);
  consecutive_ = 0;
}

Error CircuitBreaker::openError(const std::string& server) const {
  return Error{
      ErrorKind::CircuitOpen,
      fmt::format("circuit breaker open after {} consecutive server failures; the server is not called", threshold_),
      server};
}

}  // namespace cbtl::textpref
