// DiagnosticRenderer.h — turns diagnostics into text for people or JSON lines for tools.
//
// Text:  path:line:col: error[E0201]: message
//          12 | source line
//             |     ^~~~
//          = help: did you mean 'temp'?
// JSON: one object per line with severity, code, message, file, 1-based line/column and end position,
// byte offsets, children, and the rendered text (rustc-like field names; see docs/diagnostics.md).
#pragma once

#include "compiler/diag/Diagnostic.h"
#include "compiler/source/SourceManager.h"

#include <string>

namespace cbtl {

enum class DiagnosticFormat { Text, Json };

std::string renderDiagnosticText(const Diagnostic& d, const SourceManager& sources);
std::string renderDiagnosticJson(const Diagnostic& d, const SourceManager& sources);

}  // namespace cbtl
