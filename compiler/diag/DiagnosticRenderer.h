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

// `color`: ANSI colours as rustc and clang use them (severity in red or yellow, notes and help in cyan and green,
// locations in bold, the gutter in blue). Callers enable them only for a terminal (useColor()).
std::string renderDiagnosticText(const Diagnostic& d, const SourceManager& sources, bool color = false);

// Whether text for `fd` should be coloured: `mode` "always" or "never", or "auto": `fd` is a terminal and the
// NO_COLOR environment variable is unset or empty (no-color.org).
bool useColor(const std::string& mode, int fd);
std::string renderDiagnosticJson(const Diagnostic& d, const SourceManager& sources);

}  // namespace cbtl
