#include "runtime/textpref/Result.h"

#include "runtime/textpref/Redaction.h"

#include <fmt/core.h>

namespace cbtl::textpref {

const char* errorKindName(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Configuration:
      return "configuration";
    case ErrorKind::Transport:
      return "transport";
    case ErrorKind::Timeout:
      return "timeout";
    case ErrorKind::HttpStatus:
      return "http-status";
    case ErrorKind::QuotaExceeded:
      return "quota-exceeded";
    case ErrorKind::MalformedResponse:
      return "malformed-response";
    case ErrorKind::NoLogprobs:
      return "no-logprobs";
    case ErrorKind::UnusableRating:
      return "unusable-rating";
    case ErrorKind::CacheMiss:
      return "cache-miss";
    case ErrorKind::CircuitOpen:
      return "circuit-open";
    case ErrorKind::InvalidState:
      return "invalid-state";
    case ErrorKind::Io:
      return "io";
  }
  return "unknown";
}

std::string Error::describe() const {
  std::string out = errorKindName(kind);
  out += ":";
  if (!server.empty()) out += fmt::format(" server {}", server);
  if (httpStatus != 0) out += fmt::format(" returned HTTP {}", httpStatus);
  if (attempts > 0) out += fmt::format(" after {} attempt{}", attempts, attempts == 1 ? "" : "s");
  if (!server.empty() || httpStatus != 0 || attempts > 0) out += ":";
  out += " ";
  out += redactSecrets(message);
  return out;
}

}  // namespace cbtl::textpref
