// Pipeline.h — the named pass pipeline of cbtlc.
//
//   parse -> build-ast -> resolve-names -> check-types -> check-generators -> check-world -> lower -> validate-ir
//
// Each pass has a name, one entry point, and a dump of the representation it leaves behind. The
// pipeline stops after the first pass that reports errors (so later passes only ever see well-formed
// input) or after the pass named in `stopAfter`.
#pragma once

#include "compiler/driver/TranslationUnit.h"

#include <string>
#include <vector>

namespace cbtl {

enum class PipelineOutcome { Ok, InputErrors, InternalError };

struct PipelineResult {
  PipelineOutcome outcome = PipelineOutcome::Ok;
  std::string lastPass;  // the last pass that ran
  std::string dump;      // the dump after `dumpAfter`, if requested and reached
  // compileFile only: the root file was not read; inputError says why when it exists but is not a regular file or
  // is over support::kMaxSourceBytes (empty for a file that cannot be opened, say missing).
  bool rootUnread = false;
  std::string inputError;
};

const std::vector<std::string>& passNames();

// Loads `path` (read from disk) as the root file and runs the pipeline.
PipelineResult compileFile(TranslationUnit& tu, const std::string& path, const std::string& dumpAfter = "",
                           const std::string& stopAfter = "");
// The same for a file whose text is already in memory (tests, fuzzing, the REPL).
PipelineResult compileSource(TranslationUnit& tu, const std::string& path, std::string text,
                             const std::string& dumpAfter = "", const std::string& stopAfter = "");

}  // namespace cbtl
