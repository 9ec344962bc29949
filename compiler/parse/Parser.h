// Parser.h — parses one source file into an AST Module, reporting syntax errors as diagnostics.
//
// Parsing runs ANTLR's fast SLL prediction first and falls back to full LL only when SLL fails, so
// valid files pay for SLL only. ANTLR's console messages are replaced by friendly ones with stable codes
// (E01xx) and source ranges. The parse tree is an implementation detail: it lives only inside parse()
// unless a dump of it is requested.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/source/SourceManager.h"

#include <memory>
#include <string>

namespace cbtl {

struct ParseOutput {
  std::unique_ptr<Module> module;  // always set; empty on a file that cannot be read as UTF-8
  std::string treeDump;            // LISP-style parse tree, only when requested
  bool hadSyntaxErrors = false;
};

// Parses `file` (already in `sources`). Never throws for bad input.
ParseOutput parseModule(const SourceManager& sources, FileId file, DiagnosticEngine& diags, bool dumpTree = false);

}  // namespace cbtl
