#include "compiler/parse/Parser.h"

#include "compiler/ast/AstBuilder.h"
#include "compiler/driver/CompileLimits.h"
#include "compiler/parse/SyntaxErrors.h"

#include "grammar/CbtlLexer.h"
#include "grammar/CbtlParser.h"

#include <antlr4-runtime.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

namespace cbtl {
namespace {

// Returns the byte offset of the first invalid UTF-8 sequence, or npos if the text is valid.
std::size_t firstInvalidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    std::size_t len = 0;
    std::uint32_t cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    }
    if ((c & 0xE0) == 0xC0) {
      len = 2;
      cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3;
      cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4;
      cp = c & 0x07;
    } else
      return i;
    if (i + len > s.size()) return i;
    for (std::size_t k = 1; k < len; ++k) {
      const unsigned char cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (cc & 0x3F);
    }
    // Reject overlong forms, surrogates and values past U+10FFFF, which the UTF-32 decoder refuses.
    if ((len == 2 && cp < 0x80) || (len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) || cp > 0x10FFFF ||
        (cp >= 0xD800 && cp <= 0xDFFF)) {
      return i;
    }
    i += len;
  }
  return std::string::npos;
}

constexpr int kMaxNesting = CompileLimits::kMaxNesting;

}  // namespace

ParseOutput parseModule(const SourceManager& sources, FileId file, DiagnosticEngine& diags, bool dumpTree) {
  ParseOutput out;
  const std::string& text = sources.file(file).text;

  if (const std::size_t bad = firstInvalidUtf8(text); bad != std::string::npos) {
    diags
        .error("E0105", SourceRange{file, static_cast<std::uint32_t>(bad), static_cast<std::uint32_t>(bad + 1)},
               "the file is not valid UTF-8 text")
        .help("save the file as UTF-8");
    out.module = std::make_unique<Module>();
    out.module->file = file;
    out.hadSyntaxErrors = true;
    return out;
  }

  // ANTLR indexes characters by code point; diagnostics use byte offsets. Build the map only when needed.
  std::vector<std::uint32_t> byteOfCodePoint;
  const bool ascii =
      std::all_of(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0x80) == 0; });
  if (!ascii) {
    for (std::uint32_t i = 0; i < text.size(); ++i) {
      if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) byteOfCodePoint.push_back(i);
    }
    byteOfCodePoint.push_back(static_cast<std::uint32_t>(text.size()));
  }
  auto toByte = [&](std::size_t cp) -> std::uint32_t {
    if (ascii) return static_cast<std::uint32_t>(std::min(cp, text.size()));
    return cp < byteOfCodePoint.size() ? byteOfCodePoint[cp] : static_cast<std::uint32_t>(text.size());
  };
  // Tokens without text of their own (end of file, tokens conjured by error recovery) get a one-byte
  // range where they would be, so that every diagnostic has a non-empty span.
  TokenRangeFn tokenRange = [&](antlr4::Token* t) -> SourceRange {
    if (t == nullptr) return sources.insertionPoint(file, 0);
    if (t->getType() == antlr4::Token::EOF)
      return sources.insertionPoint(file, static_cast<std::uint32_t>(text.size()));
    const std::size_t start = t->getStartIndex();
    const std::size_t stop = t->getStopIndex();
    if (start == INVALID_INDEX || stop == INVALID_INDEX || stop + 1 <= start)
      return sources.insertionPoint(file, toByte(start));
    return SourceRange{file, toByte(start), toByte(stop + 1)};
  };

  antlr4::ANTLRInputStream input(text);
  input.name = sources.file(file).path;
  cbtlgrammar::CbtlLexer lexer(&input);
  lexer.removeErrorListeners();  // the lexer cannot fail: ERROR_CHAR matches anything else
  antlr4::CommonTokenStream tokens(&lexer);
  cbtlgrammar::CbtlParser parser(&tokens);
  parser.removeErrorListeners();

  // The parser and every later pass recurse on nesting; refuse absurd nesting up front so that no input
  // can exhaust the stack.
  tokens.fill();
  {
    int depth = 0;
    int prefixRun = 0;
    for (antlr4::Token* t : tokens.getTokens()) {
      const std::size_t type = t->getType();
      if (type == cbtlgrammar::CbtlLexer::LPAREN || type == cbtlgrammar::CbtlLexer::LBRACK ||
          type == cbtlgrammar::CbtlLexer::LBRACE) {
        ++depth;
      } else if (type == cbtlgrammar::CbtlLexer::RPAREN || type == cbtlgrammar::CbtlLexer::RBRACK ||
                 type == cbtlgrammar::CbtlLexer::RBRACE) {
        depth = std::max(0, depth - 1);
      }
      const bool prefix = type == cbtlgrammar::CbtlLexer::MINUS || type == cbtlgrammar::CbtlLexer::NOT ||
                          type == cbtlgrammar::CbtlLexer::IF || type == cbtlgrammar::CbtlLexer::FORALL ||
                          type == cbtlgrammar::CbtlLexer::EXISTS;
      if (t->getChannel() == antlr4::Token::DEFAULT_CHANNEL) prefixRun = prefix ? prefixRun + 1 : 0;
      // The lexer accepts any digit string; a literal past the range of a double would silently become
      // infinity, so it is refused here, where the token still has its exact range.
      if (type == cbtlgrammar::CbtlLexer::NUMBER && !std::isfinite(std::strtod(t->getText().c_str(), nullptr))) {
        std::string shown = t->getText();
        if (shown.size() > 24) shown = shown.substr(0, 21) + "...";
        diags.error("E0107", tokenRange(t), fmt::format("number '{}' is too large", shown))
            .help("numbers must be finite doubles (at most about 1.8e308)");
      }
      if (depth > kMaxNesting || prefixRun > kMaxNesting) {
        diags.error("E0108", tokenRange(t), fmt::format("nesting is too deep (more than {} levels)", kMaxNesting))
            .help("split the expression with constants or functions");
        out.module = std::make_unique<Module>();
        out.module->file = file;
        out.hadSyntaxErrors = true;
        return out;
      }
    }
  }

  // Stage 1: SLL prediction, bail out at the first error.
  parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::SLL);
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  cbtlgrammar::CbtlParser::FileContext* tree = nullptr;
  try {
    tree = parser.file();
  } catch (const antlr4::ParseCancellationException&) {
    tree = nullptr;
  }

  std::shared_ptr<SyntaxErrorStrategy> strategy;
  if (tree == nullptr) {
    // Stage 2: full LL with friendly error reporting and recovery.
    tokens.seek(0);
    parser.reset();
    parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(antlr4::atn::PredictionMode::LL);
    strategy = std::make_shared<SyntaxErrorStrategy>(diags, tokenRange, sources);
    parser.setErrorHandler(strategy);
    tree = parser.file();
    out.hadSyntaxErrors = strategy->errorsReported() > 0 || parser.getNumberOfSyntaxErrors() > 0;
    if (out.hadSyntaxErrors && strategy->errorsReported() == 0) {
      diags.error("E0101", sources.insertionPoint(file, 0), "the file could not be parsed");
    }
  }

  if (dumpTree) out.treeDump = tree->toStringTree(&parser);
  bool tooDeep = false;
  SourceRange deepAt;
  out.module = buildAst(tree, file, tokenRange, &tooDeep, &deepAt);
  if (tooDeep) {
    diags.error("E0108", deepAt, "this expression is nested too deeply (more than 1000 levels)")
        .help("split the expression with constants or functions");
    out.hadSyntaxErrors = true;
  }
  return out;
}

}  // namespace cbtl
