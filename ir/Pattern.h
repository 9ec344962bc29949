// Pattern.h — initiation patterns: globs (with named captures) and regular expressions over variable names.
//
// Glob syntax: `*` matches any run of characters (possibly empty), `?` exactly one, `{name}` a non-empty
// run bound to the capture `name`; every other character, including `[` and `]`, matches itself (variable
// names such as temp[salt] contain brackets). Matching is against the whole name; a step budget and a
// depth limit make pathological patterns fail to match instead of running long. Regexes use the
// ECMAScript grammar without back-references and must also match the whole name. Shared by the compiler (validation)
// and the runtime (matching), so both agree on what a pattern means.
#pragma once

#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace cbtl {

struct GlobPattern {
  enum class Kind { Literal, Star, One, Capture };
  struct Piece {
    Kind kind;
    std::string text;  // Literal text or capture name
  };
  std::vector<Piece> pieces;
  std::vector<std::string> captures;  // capture names in order of first appearance
};

// Parses a glob; on failure returns nullopt and sets `error` (with the byte offset in `errorAt`).
std::optional<GlobPattern> parseGlob(const std::string& text, std::string& error, std::size_t& errorAt);

// Matches a whole name. Captures already in `bindings` must match the same text; new ones are added.
// On failure `bindings` is left unchanged.
bool matchGlob(const GlobPattern& glob, const std::string& name, std::map<std::string, std::string>& bindings);

// Limits on regex patterns, which std::regex compiles recursively.
inline constexpr std::size_t kMaxRegexLength = 1000;
inline constexpr std::size_t kMaxRegexNesting = 50;

// Compiles a regex (ECMAScript, without back-references: matching takes polynomial time); on failure, or
// for a pattern longer than kMaxRegexLength or with groups nested deeper than kMaxRegexNesting, returns
// nullopt and sets `error`.
std::optional<std::regex> compileRegex(const std::string& text, std::string& error);

}  // namespace cbtl
