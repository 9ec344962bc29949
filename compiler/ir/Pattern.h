// Pattern.h — initiation patterns: globs (with named captures) and regular expressions over variable names.
//
// Glob syntax: `*` matches any run of characters (possibly empty), `?` exactly one, `{name}` a non-empty
// run bound to the capture `name`; every other character, including `[` and `]`, matches itself (variable
// names such as temp[salt] contain brackets). Matching is against the whole name. Regexes use the
// ECMAScript grammar and must also match the whole name. Shared by the compiler (validation) and the
// runtime (matching), so both agree on what a pattern means.
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

// Compiles a regex (ECMAScript); on failure returns nullopt and sets `error`.
std::optional<std::regex> compileRegex(const std::string& text, std::string& error);

}  // namespace cbtl
