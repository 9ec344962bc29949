// Result.h — explicit outcomes for the text-preference library.
//
// Nothing in cbtl::textpref lets an exception escape its public API. Every operation that can fail returns a
// Result<T> (a value or an Error) or a Status (success or an Error). An Error always says what kind of failure
// it was, which server was involved (empty for local failures), the HTTP status when there was one, and how
// many attempts were made, so that the caller can print one clear line and fall back as its generator declares.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace cbtl::textpref {

enum class ErrorKind {
  Configuration,      // bad options (e.g. top_logprobs outside 0..20, empty model name)
  Transport,          // could not connect, connection reset, TLS failure, ...
  Timeout,            // the connect or whole-request timeout expired
  HttpStatus,         // the server answered with a non-2xx status that is not retried (or retries ran out)
  QuotaExceeded,      // HTTP 429 with error code insufficient_quota: never retried
  MalformedResponse,  // body is not JSON or lacks the chat-completions shape
  NoLogprobs,         // the response has no usable top_logprobs for the first token
  UnusableRating,     // logprobs present but too little probability mass on the 11 rating tokens
  CacheMiss,          // read-only cache mode and the entry is absent: the network is never reached
  CircuitOpen,        // the circuit breaker is open (CircuitBreaker.h): the server is no longer called
  InvalidState,       // a saved model state is not valid JSON or does not match the expected schema
  Io,                 // a file could not be read or written
};

// Stable lower-case name of an ErrorKind, used in messages and JSON.
const char* errorKindName(ErrorKind kind);

struct Error {
  Error() = default;
  Error(ErrorKind kind_, std::string message_, std::string server_ = {}, int httpStatus_ = 0, int attempts_ = 0)
      : kind(kind_),
        message(std::move(message_)),
        server(std::move(server_)),
        httpStatus(httpStatus_),
        attempts(attempts_) {}

  ErrorKind kind = ErrorKind::Io;
  std::string message;  // what went wrong, in one sentence; never contains the API key (Redaction.h)
  std::string server;   // "host:port" of the server involved, empty when no server was involved
  int httpStatus = 0;   // last HTTP status seen, 0 when there was none
  int attempts = 0;     // number of HTTP attempts made, 0 when none were made

  // One line: "<kind>: server <server> returned HTTP <status> after <n> attempts: <message>" with the parts
  // that are unknown left out. The message is passed through redactSecrets() (Redaction.h) once more, so a
  // "Bearer ..." or "sk-..." token never reaches a printed line even if a message was built unredacted.
  std::string describe() const;
};

// A value of type T or an Error. Accessing the wrong alternative is a programming error (std::get throws
// std::bad_variant_access), so callers test ok() first.
template <typename T>
class Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : data_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return std::holds_alternative<T>(data_); }
  explicit operator bool() const { return ok(); }
  const T& value() const& { return std::get<T>(data_); }
  T& value() & { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }
  const Error& error() const { return std::get<Error>(data_); }

 private:
  std::variant<T, Error> data_;
};

// Success, or an Error.
class Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), failed_(true) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const { return error_; }

 private:
  Error error_;
  bool failed_ = false;
};

}  // namespace cbtl::textpref
