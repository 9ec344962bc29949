// cbtlc_fuzz.cpp — libFuzzer target: the whole cbtlc pipeline on arbitrary bytes.
//
// Each input is compiled as the root file of a fresh translation unit (parse -> ... -> validate-ir, with
// the AST dump after resolve-names so the printer runs too). Every diagnostic is rendered as text and as
// JSON, and a graph that compiled is printed in all three formats. Besides crashes, leaks and sanitizer
// reports, the target aborts on two contract violations the front end promises never to commit:
//   - a diagnostic whose primary span (or a child's span) is not inside a file of the translation unit;
//   - an internal error (E0901: lowering produced a graph that the IR validator rejects).
// Built only with -DCBTL_FUZZ=ON and clang (see scripts/fuzz.sh).
#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/driver/Pipeline.h"
#include "ir/GraphPrinter.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

void requireInside(const cbtl::SourceRange& r, const cbtl::SourceManager& sources, const cbtl::Diagnostic& d) {
  const bool ok =
      r.valid() && r.file < sources.fileCount() && r.begin <= r.end && r.end <= sources.file(r.file).text.size();
  if (!ok) {
    std::fprintf(stderr, "diagnostic %s (%s) has a span outside its file\n", d.code.c_str(), d.message.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cbtl::TranslationUnit tu(cbtl::CompileOptions{});
  // A path in a directory that does not exist: relative imports resolve next to it and cannot be read.
  const std::string path = "/nonexistent-cbtl-fuzz/input.cbtl";
  const cbtl::PipelineResult result =
      cbtl::compileSource(tu, path, std::string(reinterpret_cast<const char*>(data), size), "resolve-names");
  for (const auto& d : tu.diags.sorted()) {
    requireInside(d.range, tu.sources, d);
    for (const auto& c : d.children) {
      if (c.range.valid()) requireInside(c.range, tu.sources, d);
    }
    (void)cbtl::renderDiagnosticText(d, tu.sources);
    (void)cbtl::renderDiagnosticJson(d, tu.sources);
  }
  if (result.outcome == cbtl::PipelineOutcome::InternalError) {
    std::fprintf(stderr, "internal error after pass %s\n", result.lastPass.c_str());
    std::abort();
  }
  if (result.outcome == cbtl::PipelineOutcome::Ok) {
    (void)cbtl::ir::toText(tu.graph);
    (void)cbtl::ir::toJson(tu.graph);
    (void)cbtl::ir::toDot(tu.graph);
  }
  return 0;
}
