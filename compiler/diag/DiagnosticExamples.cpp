#include "compiler/diag/DiagnosticExamples.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace cbtl {

// Generated from compiler/diag/examples (cmake/EmbedFiles.cmake).
const std::map<std::string, std::string_view>& diagnosticExampleFiles();

namespace {

constexpr std::string_view kMainFile = "example.cbtl";

// "E0204/right/shared.cbtl" -> {"E0204", "right", "shared.cbtl"}.
struct ExamplePath {
  std::string code, side, file;
};
ExamplePath split(const std::string& key) {
  const std::size_t a = key.find('/');
  const std::size_t b = key.find('/', a + 1);
  if (a == std::string::npos || b == std::string::npos)
    throw std::logic_error("diagnostic example outside <CODE>/{wrong,right}/: " + key);
  return {key.substr(0, a), key.substr(a + 1, b - a - 1), key.substr(b + 1)};
}

std::vector<DiagnosticExample> loadExamples() {
  std::map<std::string, DiagnosticExample> byCode;
  for (const auto& [key, text] : diagnosticExampleFiles()) {
    const ExamplePath p = split(key);
    DiagnosticExample& e = byCode[p.code];
    if (e.code.empty()) e.code = std::string_view(key).substr(0, p.code.size());
    const bool wrong = p.side == "wrong";
    if (p.file == kMainFile) {
      (wrong ? e.wrong : e.right) = text;
    } else {
      e.imported = std::string_view(key).substr(key.size() - p.file.size());
      (wrong ? e.importedWrong : e.importedRight) = text;
    }
  }
  std::vector<DiagnosticExample> out;
  for (auto& [code, e] : byCode) out.push_back(e);
  return out;
}

}  // namespace

// Each wrong program produces its code; each right one compiles with no diagnostic at all
// (tests/unit/compiler/DiagnosticExamplesTest.cpp). Programs are whole files, as small as the code allows, kept as
// files under compiler/diag/examples/<CODE>/{wrong,right}/ (each folder can be checked with cbtlc as it is).
const std::vector<DiagnosticExample>& diagnosticExamples() {
  static const std::vector<DiagnosticExample> examples = loadExamples();
  return examples;
}

const DiagnosticExample* exampleFor(std::string_view code) {
  const auto& all = diagnosticExamples();
  const auto it = std::find_if(all.begin(), all.end(), [&](const DiagnosticExample& e) { return e.code == code; });
  return it == all.end() ? nullptr : &*it;
}

}  // namespace cbtl
