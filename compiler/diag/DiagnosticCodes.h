// DiagnosticCodes.h — the catalogue of stable diagnostic codes.
//
// Codes are grouped by phase: E01xx syntax, E02xx names and imports, E03xx types and domains, E04xx
// personalized constraint generators, E05xx skills and tasks, E06xx the world (clearances, allow statements and
// the scene names they use), E09xx internal (IR validation). Warnings
// use W and the same grouping. A code, once published, keeps its meaning; `cbtlc explain CODE` prints
// the long explanation.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cbtl {

struct DiagnosticCodeInfo {
  std::string_view code;
  std::string_view summary;      // one line
  std::string_view explanation;  // a paragraph with an example, for `cbtlc explain`
};

// Every code, sorted by code.
const std::vector<DiagnosticCodeInfo>& diagnosticCodes();
// The entry for a code (case-insensitive), or nullptr.
const DiagnosticCodeInfo* findDiagnosticCode(std::string_view code);

}  // namespace cbtl
