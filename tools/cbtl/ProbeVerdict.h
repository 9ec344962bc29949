// ProbeVerdict.h — the last line of `cbtl llm probe`: usable, or which failure makes the server unusable.
//
// The probe reduces what went wrong to the first failure it met, as a textpref::Error: Transport or Timeout
// (the server never answered), HttpStatus (with its code), QuotaExceeded, MalformedResponse, NoLogprobs (an
// answer without top_logprobs) or UnusableRating (too little mass on 0..10). probeVerdict() names that failure;
// every quoted server text is redacted (Error::describe(), Redaction.h). Each verdict starts with
// "verdict: unusable: <failure>:" so that scripts and tests can match it.
#pragma once

#include "runtime/textpref/Result.h"

#include <fmt/core.h>

#include <string>

namespace cbtl::cli {

inline std::string probeVerdict(const textpref::Error& failure, const std::string& apiKeyEnv) {
  using textpref::ErrorKind;
  const std::string detail = failure.describe();
  switch (failure.kind) {
    case ErrorKind::Transport:
    case ErrorKind::Timeout:
      return fmt::format(
          "verdict: unusable: transport error: the server did not answer ({}). Check --base-url, that "
          "the server runs, and --timeout-ms.",
          detail);
    case ErrorKind::HttpStatus:
      return fmt::format("verdict: unusable: HTTP status {}: {}.{}", failure.httpStatus, detail,
                         failure.httpStatus == 401 || failure.httpStatus == 403
                             ? fmt::format(" Check the API key in ${}.", apiKeyEnv)
                             : std::string());
    case ErrorKind::QuotaExceeded:
      return fmt::format("verdict: unusable: quota exceeded (HTTP {}): {}. Waiting does not help; check billing.",
                         failure.httpStatus, detail);
    case ErrorKind::MalformedResponse:
      return fmt::format("verdict: unusable: malformed reply: {}. Is --base-url an OpenAI-compatible /v1 endpoint?",
                         detail);
    case ErrorKind::NoLogprobs:
      return "verdict: unusable: no logprobs: the server answered without top_logprobs, which rating constraints "
             "need. Use another server or model, or the offline descriptor model (the default backend, no server "
             "needed).";
    case ErrorKind::UnusableRating:
      return fmt::format("verdict: unusable: low coverage: {}. Use another model, or the offline descriptor model.",
                         detail);
    default:
      return fmt::format("verdict: unusable: {}", detail);
  }
}

}  // namespace cbtl::cli
