#include "runtime/textpref/Redaction.h"

#include <cctype>
#include <cstdlib>

namespace cbtl::textpref {
namespace {

constexpr std::size_t kMinBearerToken = 8;  // "the bearer of bad news" is not a credential

bool isKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '*' || c == '.';
}

// Length of the key-character run starting at `pos`, without a trailing '.' (end of a sentence).
std::size_t keyRun(std::string_view s, std::size_t pos) {
  std::size_t end = pos;
  while (end < s.size() && isKeyChar(s[end])) ++end;
  while (end > pos && s[end - 1] == '.') --end;
  return end - pos;
}

bool startsWithBearer(std::string_view s, std::size_t pos) {
  static constexpr std::string_view word = "bearer";
  if (pos + word.size() >= s.size()) return false;
  if (pos > 0 && std::isalnum(static_cast<unsigned char>(s[pos - 1]))) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[pos + i])) != word[i]) return false;
  return s[pos + word.size()] == ' ';
}

std::string replaceAll(std::string_view text, std::string_view needle) {
  std::string out;
  std::size_t from = 0;
  for (std::size_t at = text.find(needle); at != std::string_view::npos; at = text.find(needle, from)) {
    out.append(text.substr(from, at - from));
    out.append(kRedacted);
    from = at + needle.size();
  }
  out.append(text.substr(from));
  return out;
}

}  // namespace

std::string redactSecrets(std::string_view text, std::string_view secret) {
  const std::string withoutKey = secret.size() >= kMinSecretLength ? replaceAll(text, secret) : std::string(text);
  const std::string_view s = withoutKey;
  std::string out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    if (startsWithBearer(s, i)) {
      std::size_t j = i + 6;
      while (j < s.size() && s[j] == ' ') ++j;
      const std::size_t n = keyRun(s, j);
      if (n >= kMinBearerToken) {
        out.append(s.substr(i, 6));
        out.push_back(' ');
        out.append(kRedacted);
        i = j + n;
        continue;
      }
    }
    const bool boundary = i == 0 || !isKeyChar(s[i - 1]);
    if (boundary && s.substr(i, 3) == "sk-") {
      const std::size_t n = keyRun(s, i);
      if (n >= 3 + 4) {
        out.append(kRedacted);
        i += n;
        continue;
      }
    }
    out.push_back(s[i]);
    ++i;
  }
  return out;
}

std::string secretFromEnvironment(const std::string& envName) {
  if (envName.empty()) return {};
  const char* value = std::getenv(envName.c_str());
  return value == nullptr ? std::string() : std::string(value);
}

}  // namespace cbtl::textpref
