// AstBuilder.h — builds a Module from the ANTLR parse tree in one pass.
//
// Internal to the parser: callers use parseModule() (parse/Parser.h). The builder tolerates the partial
// trees that error recovery leaves behind (missing children become empty names or are skipped), so a
// file with syntax errors still yields an AST; the pipeline stops after parsing in that case anyway.
#pragma once

#include "compiler/ast/Ast.h"

#include <functional>
#include <memory>

namespace cbtlgrammar {
class CbtlParser;
}
namespace antlr4 {
class Token;
}

namespace cbtl {

using TokenRangeFn = std::function<SourceRange(antlr4::Token*)>;

// `file` is a CbtlParser::FileContext*; kept opaque here so that only .cpp files see generated headers.
// Sets *depthExceeded (and *depthRange) when an expression was nested past the builder's limit and cut.
std::unique_ptr<Module> buildAst(void* fileContext, FileId file, const TokenRangeFn& tokenRange, bool* depthExceeded,
                                 SourceRange* depthRange);

}  // namespace cbtl
