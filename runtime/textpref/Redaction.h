// Redaction.h — keeps API keys out of every message that quotes a server.
//
// A server may echo the credential it was sent (OpenAI: "Incorrect API key provided: sk-...", some proxies:
// "invalid header Authorization: Bearer ..."). Every error message, warning and probe line that quotes a server
// passes through redactSecrets() before it is stored in an Error or printed.
//
// Contract of redactSecrets(text, secret):
//  - every occurrence of `secret` is replaced by kRedacted, when `secret` has at least kMinSecretLength
//    characters (a shorter value would garble ordinary words; such a key is still caught by the patterns below);
//  - every "Bearer <token>" (case-insensitive "bearer", one or more spaces, a token of at least 8 key characters)
//    becomes "Bearer [redacted]";
//  - every token that starts with "sk-" at a word boundary and continues with at least 4 key characters
//    (letters, digits, '-', '_', '*', '.') becomes kRedacted;
//  - nothing else changes. The result never contains `secret` (when long enough) and is idempotent.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace cbtl::textpref {

inline constexpr std::string_view kRedacted = "[redacted]";
inline constexpr std::size_t kMinSecretLength = 4;

std::string redactSecrets(std::string_view text, std::string_view secret = {});

// The value of environment variable `envName` ("" when unset or when envName is empty), for redaction only.
std::string secretFromEnvironment(const std::string& envName);

}  // namespace cbtl::textpref
