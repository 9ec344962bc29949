#include "compiler/diag/DiagnosticEngine.h"

#include <algorithm>
#include <tuple>

namespace cbtl {

Diagnostic& DiagnosticEngine::report(Severity severity, std::string code, SourceRange range, std::string message) {
  if (severity == Severity::Warning && warningsAsErrors_) severity = Severity::Error;
  if (severity == Severity::Error) {
    ++errors_;
    if (errors_ > errorLimit_) {
      ++dropped_;
      scratch_ = Diagnostic{};
      return scratch_;
    }
  } else {
    ++warnings_;
  }
  kept_.push_back(Diagnostic{severity, std::move(code), range, std::move(message), {}});
  return kept_.back();
}

std::vector<Diagnostic> DiagnosticEngine::sorted() const {
  std::vector<Diagnostic> out = kept_;
  std::stable_sort(out.begin(), out.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.range.file, a.range.begin, a.severity, a.code, a.message) <
           std::tie(b.range.file, b.range.begin, b.severity, b.code, b.message);
  });
  return out;
}

}  // namespace cbtl
