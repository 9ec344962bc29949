// Sha256.h — SHA-256 digests through OpenSSL's EVP interface, for response-cache keys.
#pragma once

#include <string>
#include <string_view>

namespace cbtl::textpref {

// Lower-case hexadecimal SHA-256 of `data` (64 characters). Returns "" only if OpenSSL itself fails.
std::string sha256Hex(std::string_view data);

}  // namespace cbtl::textpref
