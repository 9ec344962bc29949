// DiagnosticEngine.h — collects the diagnostics of one translation unit.
//
// Passes report into the engine; the pipeline stops between passes once there are errors. Output
// order is deterministic: by file, then offset, then severity, then code and text (the order in which
// passes happened to report does not matter). After `errorLimit` errors further errors are counted but
// not kept, and the renderer says how many were dropped.
#pragma once

#include "compiler/diag/Diagnostic.h"

#include <cstddef>
#include <vector>

namespace cbtl {

class DiagnosticEngine {
 public:
  explicit DiagnosticEngine(std::size_t errorLimit = 50) : errorLimit_(errorLimit) {}

  // Adds a diagnostic and returns it so callers can attach notes. The reference stays valid until the
  // next report. Diagnostics past the error limit go to a scratch slot that is discarded.
  Diagnostic& report(Severity severity, std::string code, SourceRange range, std::string message);
  Diagnostic& error(std::string code, SourceRange range, std::string message) {
    return report(Severity::Error, std::move(code), range, std::move(message));
  }
  Diagnostic& warning(std::string code, SourceRange range, std::string message) {
    return report(Severity::Warning, std::move(code), range, std::move(message));
  }

  std::size_t errorCount() const { return errors_; }
  std::size_t warningCount() const { return warnings_; }
  bool hasErrors() const { return errors_ > 0; }
  std::size_t droppedCount() const { return dropped_; }
  bool warningsAsErrors() const { return warningsAsErrors_; }
  void setWarningsAsErrors(bool on) { warningsAsErrors_ = on; }

  // The kept diagnostics in deterministic order.
  std::vector<Diagnostic> sorted() const;

 private:
  std::size_t errorLimit_;
  std::size_t errors_ = 0;
  std::size_t warnings_ = 0;
  std::size_t dropped_ = 0;
  bool warningsAsErrors_ = false;
  std::vector<Diagnostic> kept_;
  Diagnostic scratch_;
};

}  // namespace cbtl
