// TranslationUnit.h — everything one compilation owns: sources, modules (the root file first, then its
// imports in load order), diagnostics, types, the symbol table and the constraint graph. No global state:
// two translation units never share anything, so compilations can run side by side.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"
#include "compiler/source/SourceManager.h"
#include "compiler/world/WorldCheck.h"
#include "ir/ConstraintGraph.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cbtl {

struct CompileOptions {
  std::string stdlibDir;  // empty: the embedded standard library
  std::size_t errorLimit = 50;
  bool warningsAsErrors = false;
};

struct TranslationUnit {
  explicit TranslationUnit(CompileOptions opts) : options(std::move(opts)), diags(options.errorLimit) {
    diags.setWarningsAsErrors(options.warningsAsErrors);
  }

  CompileOptions options;
  SourceManager sources;
  DiagnosticEngine diags;
  TypeContext types;
  std::vector<std::unique_ptr<Module>> modules;
  std::map<FileId, std::string> parseTrees;  // filled when a dump of the parse pass is requested
  GlobalSymbols symbols;
  WorldCheckResult world;  // what check-world read
  ir::ConstraintGraph graph;
  FileId root = kNoFile;
};

}  // namespace cbtl
