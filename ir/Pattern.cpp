#include "ir/Pattern.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace cbtl {

std::optional<GlobPattern> parseGlob(const std::string& text, std::string& error, std::size_t& errorAt) {
  GlobPattern g;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '*') {
      // "**" means the same as "*"; one piece keeps the matcher's recursion bounded by the name's length.
      if (g.pieces.empty() || g.pieces.back().kind != GlobPattern::Kind::Star)
        g.pieces.push_back({GlobPattern::Kind::Star, ""});
    } else if (c == '?') {
      g.pieces.push_back({GlobPattern::Kind::One, ""});
    } else if (c == '{') {
      const std::size_t close = text.find('}', i);
      if (close == std::string::npos) {
        error = "'{' opens a capture that is never closed with '}'";
        errorAt = i;
        return std::nullopt;
      }
      std::string name = text.substr(i + 1, close - i - 1);
      bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_');
      for (char ch : name) ok = ok && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_');
      if (!ok) {
        error =
            name.empty() ? "a capture needs a name, as in {ing}" : "capture name '" + name + "' is not an identifier";
        errorAt = i;
        return std::nullopt;
      }
      g.pieces.push_back({GlobPattern::Kind::Capture, name});
      bool seen = false;
      for (const auto& n : g.captures) seen = seen || n == name;
      if (!seen) g.captures.push_back(name);
      i = close;
    } else if (c == '}') {
      error = "'}' without a matching '{'";
      errorAt = i;
      return std::nullopt;
    } else {
      if (!g.pieces.empty() && g.pieces.back().kind == GlobPattern::Kind::Literal) {
        g.pieces.back().text += c;
      } else {
        g.pieces.push_back({GlobPattern::Kind::Literal, std::string(1, c)});
      }
    }
  }
  return g;
}

namespace {

// Backtracking matcher; patterns are short, so the worst case stays small in practice. A budget of steps
// bounds pathological patterns such as "*a*a*a*a*b", and a depth limit bounds the recursion (one level
// per piece) for absurdly long patterns and names; past either the pattern does not match.
constexpr std::size_t kMaxGlobDepth = 2000;

bool matchFrom(const GlobPattern& g, std::size_t p, const std::string& s, std::size_t i,
               std::map<std::string, std::string>& b, long& budget) {
  if (--budget < 0 || p > kMaxGlobDepth) return false;
  if (p == g.pieces.size()) return i == s.size();
  const auto& piece = g.pieces[p];
  switch (piece.kind) {
    case GlobPattern::Kind::Literal:
      if (s.compare(i, piece.text.size(), piece.text) != 0) return false;
      return matchFrom(g, p + 1, s, i + piece.text.size(), b, budget);
    case GlobPattern::Kind::One:
      return i < s.size() && matchFrom(g, p + 1, s, i + 1, b, budget);
    case GlobPattern::Kind::Star:
      for (std::size_t j = i; j <= s.size(); ++j) {
        if (matchFrom(g, p + 1, s, j, b, budget)) return true;
      }
      return false;
    case GlobPattern::Kind::Capture: {
      auto it = b.find(piece.text);
      if (it != b.end()) {
        if (s.compare(i, it->second.size(), it->second) != 0) return false;
        return matchFrom(g, p + 1, s, i + it->second.size(), b, budget);
      }
      for (std::size_t j = i + 1; j <= s.size(); ++j) {
        b[piece.text] = s.substr(i, j - i);
        if (matchFrom(g, p + 1, s, j, b, budget)) return true;
      }
      b.erase(piece.text);
      return false;
    }
  }
  return false;
}

}  // namespace

bool matchGlob(const GlobPattern& glob, const std::string& name, std::map<std::string, std::string>& bindings) {
  std::map<std::string, std::string> trial = bindings;
  long budget = 100000;
  if (!matchFrom(glob, 0, name, 0, trial, budget)) return false;
  bindings = std::move(trial);
  return true;
}

namespace {

// The deepest nesting of groups in an ECMAScript pattern (escapes and bracket expressions skipped).
std::size_t groupDepth(const std::string& text) {
  std::size_t depth = 0, deepest = 0;
  bool inClass = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\\') {
      ++i;
    } else if (inClass) {
      inClass = c != ']';
    } else if (c == '[') {
      inClass = true;
    } else if (c == '(') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ')' && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

}  // namespace

std::optional<std::regex> compileRegex(const std::string& text, std::string& error) {
  // std::regex compiles and matches recursively: a long or deeply nested pattern could exhaust the stack
  // (a pattern comes from a .cbtl file, so from anyone). Name patterns are short; these limits are generous.
  if (text.size() > kMaxRegexLength) {
    error = "the regular expression is longer than " + std::to_string(kMaxRegexLength) + " characters";
    return std::nullopt;
  }
  if (groupDepth(text) > kMaxRegexNesting) {
    error = "the regular expression nests groups more than " + std::to_string(kMaxRegexNesting) + " deep";
    return std::nullopt;
  }
  try {
#if defined(__GLIBCXX__)
    // libstdc++'s breadth-first executor matches in polynomial time (no exponential backtracking on patterns
    // such as "(a*)*b"); it refuses back-references, which name patterns do not need.
    return std::regex(text, std::regex::ECMAScript | std::regex_constants::__polynomial);
#else
    return std::regex(text, std::regex::ECMAScript);
#endif
  } catch (const std::regex_error& e) {
    error = e.what();
    return std::nullopt;
  }
}

}  // namespace cbtl
