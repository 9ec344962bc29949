// AstPrinter.h — a dump of the AST, with resolutions and types once the semantic passes have run.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/source/SourceManager.h"

#include <string>

namespace cbtl {

std::string dumpAst(const Module& module, const SourceManager& sources);

}  // namespace cbtl
