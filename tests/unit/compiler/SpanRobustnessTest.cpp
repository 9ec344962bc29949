// Every diagnostic points into the source: the golden inputs, and mutations of them (truncated at every
// Nth byte, tokens deleted at random with a fixed seed), are compiled in-process and each diagnostic must
// have a known code, a message, and a valid, non-empty primary span inside its file (children too, when
// they have a location). No input may produce an internal error or an exception.
#include "compiler/diag/DiagnosticCodes.h"
#include "compiler/driver/Pipeline.h"

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace cbtl {
namespace {

namespace fs = std::filesystem;
constexpr std::size_t kCutsPerFile = 12;  // truncations of each input
constexpr int kDeletionsPerFile = 8;      // token-deletion mutants of each input

std::vector<fs::path> goldenInputs() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(CBTL_GOLDEN_DIR)) {
    if (entry.is_regular_file() && entry.path().extension() == ".cbtl") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Checks one compilation; returns the number of diagnostics checked.
std::size_t checkSpans(const std::string& path, const std::string& text, const std::string& what) {
  TranslationUnit tu(CompileOptions{});
  PipelineResult result;
  EXPECT_NO_THROW(result = compileSource(tu, path, text)) << what;
  EXPECT_NE(result.outcome, PipelineOutcome::InternalError) << what;
  auto inside = [&](const SourceRange& r, const Diagnostic& d, const char* role) {
    ASSERT_TRUE(r.valid()) << what << ": " << d.code << " " << role << " has no file";
    ASSERT_LT(r.file, tu.sources.fileCount()) << what << ": " << d.code;
    const std::size_t size = tu.sources.file(r.file).text.size();
    EXPECT_LE(r.end, size) << what << ": " << d.code << " " << role << " ends past its file";
    if (size > 0) {
      EXPECT_LT(r.begin, r.end) << what << ": " << d.code << " (" << d.message << ") " << role << " is empty at byte "
                                << r.begin;
    }
  };
  const auto diags = tu.diags.sorted();
  for (const auto& d : diags) {
    EXPECT_NE(findDiagnosticCode(d.code), nullptr) << what << ": unknown code " << d.code;
    EXPECT_FALSE(d.message.empty()) << what << ": " << d.code;
    inside(d.range, d, "span");
    for (const auto& c : d.children) {
      EXPECT_FALSE(c.message.empty()) << what << ": " << d.code;
      if (c.range.valid()) inside(c.range, d, "child span");
    }
  }
  return diags.size();
}

// Token boundaries by a rough lexer (names, numbers, strings, single punctuation); enough for mutation.
std::vector<std::pair<std::size_t, std::size_t>> roughTokens(const std::string& s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (std::isspace(c)) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    if (std::isalnum(c) || c == '_') {
      while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_' || s[j] == '.')) ++j;
    } else if (c == '"') {
      while (j < s.size() && s[j] != '"' && s[j] != '\n') ++j;
      if (j < s.size() && s[j] == '"') ++j;
    }
    out.emplace_back(i, j);
    i = j;
  }
  return out;
}

TEST(SpanRobustness, GoldenInputsAndTheirMutations) {
  const auto inputs = goldenInputs();
  ASSERT_GT(inputs.size(), 50u) << "golden inputs not found under " << CBTL_GOLDEN_DIR;
  std::mt19937 rng(20241122);  // fixed seed: the same mutations on every run
  std::size_t compiled = 0, diagnostics = 0;
  for (const auto& path : inputs) {
    const std::string text = readAll(path);
    const std::string name = path.string();
    diagnostics += checkSpans(name, text, name);
    ++compiled;
    // Truncations at every Nth byte, N chosen for about kCutsPerFile cuts per file.
    const std::size_t stride = std::max<std::size_t>(7, text.size() / kCutsPerFile);
    for (std::size_t cut = 1; cut < text.size(); cut += stride) {
      diagnostics += checkSpans(name, text.substr(0, cut), name + " truncated at byte " + std::to_string(cut));
      ++compiled;
    }
    // Deletions of one to three random tokens.
    const auto tokens = roughTokens(text);
    if (tokens.empty()) continue;
    for (int m = 0; m < kDeletionsPerFile; ++m) {
      std::string mutated = text;
      std::vector<std::size_t> picks;
      const int count = 1 + static_cast<int>(rng() % 3);
      for (int k = 0; k < count; ++k) picks.push_back(rng() % tokens.size());
      std::sort(picks.rbegin(), picks.rend());
      picks.erase(std::unique(picks.begin(), picks.end()), picks.end());
      std::string removed;
      for (std::size_t p : picks) {
        const auto [b, e] = tokens[p];
        removed += " #" + std::to_string(p);
        mutated.erase(b, e - b);
      }
      diagnostics += checkSpans(name, mutated, name + " without tokens" + removed);
      ++compiled;
    }
  }
  // The mutations must actually exercise the error paths.
  EXPECT_GT(diagnostics, compiled);
  RecordProperty("compilations", static_cast<int>(compiled));
  RecordProperty("diagnostics", static_cast<int>(diagnostics));
}

// Inputs that once broke the span contract, kept as explicit cases.
TEST(SpanRobustness, EdgeCases) {
  for (const std::string& text :
       {std::string(""), std::string("var"), std::string("var x : real"), std::string("import \""),
        std::string("import"), std::string("\"unterminated"), std::string("/* open"), std::string("require (x < 1;"),
        std::string("domain"), std::string("enum E {"), std::string("\xff"), std::string("var x : real in 0 .. 1e999;"),
        std::string("personal p(x: real) { when x ~ \"{\""), std::string(")))"), std::string("task t = ;"),
        std::string("skill s { do { f( } }")}) {
    checkSpans("edge.cbtl", text, "edge case '" + text + "'");
  }
}

}  // namespace
}  // namespace cbtl
