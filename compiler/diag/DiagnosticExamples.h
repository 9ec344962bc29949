// DiagnosticExamples.h — for every diagnostic code, a small program that produces it and the corrected program,
// shown by `cbtlc explain CODE` under "Wrong:" and "Right:".
//
// The programs are whole files named example.cbtl, kept under compiler/diag/examples/<CODE>/wrong/ and right/. A few
// codes need a second file (an import): `imported` names it, with its text beside the wrong program (empty: the wrong
// program imports a file that does not exist) and beside the right one. The test compiles every pair: the wrong one
// must report the code, the right one must compile without any diagnostic, so the examples cannot drift from the
// compiler.
#pragma once

#include <string_view>
#include <vector>

namespace cbtl {

struct DiagnosticExample {
  std::string_view code;
  std::string_view wrong;
  std::string_view right;
  std::string_view imported;  // a second file's name, or empty
  std::string_view importedWrong;
  std::string_view importedRight;
};

const std::vector<DiagnosticExample>& diagnosticExamples();

// The example of `code`; null for a code no input can produce (E0901).
const DiagnosticExample* exampleFor(std::string_view code);

}  // namespace cbtl
