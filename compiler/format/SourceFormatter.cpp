#include "compiler/format/SourceFormatter.h"

#include "grammar/CbtlLexer.h"
#include "grammar/CbtlParser.h"

#include <antlr4-runtime.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace cbtl {

namespace {

using Lexer = cbtlgrammar::CbtlLexer;

struct Token {
  std::size_t type = 0;
  std::size_t index = 0;  // in the token stream (OperatorRoles)
  std::string text;
  int line = 0;     // 0-based
  int col = 0;      // code points from the start of the line
  int endLine = 0;  // the line it ends on (a block comment may span lines)
  int endCol = 0;   // the column just after it, on endLine
  bool comment() const { return type == Lexer::LINE_COMMENT || type == Lexer::BLOCK_COMMENT; }
};

int codePoints(std::string_view s) {
  return static_cast<int>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// Every token but whitespace of a filled token stream, in order, with its position.
std::vector<Token> tokensOf(antlr4::CommonTokenStream& stream) {
  std::vector<Token> out;
  for (antlr4::Token* t : stream.getTokens()) {
    if (t->getType() == Lexer::WS || t->getType() == antlr4::Token::EOF) continue;
    Token k;
    k.type = t->getType();
    k.index = t->getTokenIndex();
    k.text = t->getText();
    // Trailing blanks of a line comment are trailing whitespace of the line, not part of what it says.
    if (k.type == Lexer::LINE_COMMENT) k.text.erase(k.text.find_last_not_of(" \t\f") + 1);
    k.line = static_cast<int>(t->getLine()) - 1;
    k.col = static_cast<int>(t->getCharPositionInLine());
    const std::size_t lastBreak = k.text.rfind('\n');
    if (lastBreak == std::string::npos) {
      k.endLine = k.line;
      k.endCol = k.col + codePoints(k.text);
    } else {
      k.endLine = k.line + static_cast<int>(std::count(k.text.begin(), k.text.end(), '\n'));
      k.endCol = codePoints(std::string_view(k.text).substr(lastBreak + 1));
    }
    out.push_back(std::move(k));
  }
  return out;
}

std::vector<Token> lex(std::string_view text) {
  antlr4::ANTLRInputStream input{std::string(text)};
  Lexer lexer(&input);
  lexer.removeErrorListeners();
  antlr4::CommonTokenStream stream(&lexer);
  stream.fill();
  return tokensOf(stream);
}

// What the parse tree says about the operators whose spacing the tokens alone cannot decide: `<` `>` compare or
// enclose type arguments, `-` subtracts or negates. Token indices of the stream.
struct OperatorRoles {
  std::set<std::size_t> binary;  // comparison, additive and multiplicative operators
  std::set<std::size_t> prefix;  // unary minus
  bool parsed = false;           // false: the file did not parse, and nothing is known
  bool typeBracket(const Token& t) const {
    return parsed && (t.type == Lexer::LT || t.type == Lexer::GT) && !binary.count(t.index);
  }
};

void collectRoles(antlr4::tree::ParseTree* node, OperatorRoles& roles) {
  using P = cbtlgrammar::CbtlParser;
  if (auto* c = dynamic_cast<P::CmpExprContext*>(node)) roles.binary.insert(c->op->getTokenIndex());
  if (auto* c = dynamic_cast<P::AddExprContext*>(node)) roles.binary.insert(c->op->getTokenIndex());
  if (auto* c = dynamic_cast<P::MulExprContext*>(node)) roles.binary.insert(c->op->getTokenIndex());
  if (auto* c = dynamic_cast<P::NegExprContext*>(node)) roles.prefix.insert(c->MINUS()->getSymbol()->getTokenIndex());
  if (auto* c = dynamic_cast<P::LengthLitContext*>(node); c != nullptr && c->MINUS() != nullptr)
    roles.prefix.insert(c->MINUS()->getSymbol()->getTokenIndex());
  for (antlr4::tree::ParseTree* child : node->children) collectRoles(child, roles);
}

// The file's tokens and its operators' roles. A file that does not parse gets no roles (its operators keep the
// author's spacing); formatSource's callers parse it first anyway.
std::vector<Token> lexAndParse(std::string_view text, OperatorRoles& roles) {
  antlr4::ANTLRInputStream input{std::string(text)};
  Lexer lexer(&input);
  lexer.removeErrorListeners();
  antlr4::CommonTokenStream stream(&lexer);
  stream.fill();
  cbtlgrammar::CbtlParser parser(&stream);
  parser.removeErrorListeners();
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  try {
    collectRoles(parser.file(), roles);
    roles.parsed = true;
  } catch (const antlr4::ParseCancellationException&) {
    roles = OperatorRoles{};
  }
  return tokensOf(stream);
}

bool isOpener(std::size_t t) { return t == Lexer::LPAREN || t == Lexer::LBRACK || t == Lexer::LBRACE; }
bool isCloser(std::size_t t) { return t == Lexer::RPAREN || t == Lexer::RBRACK || t == Lexer::RBRACE; }

// Operators and keywords that join two phrases: one space on each side.
bool joinsPhrases(std::size_t t) {
  switch (t) {
    case Lexer::ASSIGN:
    case Lexer::EQ:
    case Lexer::NEQ:
    case Lexer::LE:
    case Lexer::GE:
    case Lexer::ARROW_FAT:
    case Lexer::IFF:
    case Lexer::ARROW:
    case Lexer::DOTDOT:
    case Lexer::TILDE:
    case Lexer::PLUS:
    case Lexer::STAR:
    case Lexer::SLASH:
    case Lexer::PERCENT:
    case Lexer::AND:
    case Lexer::OR:
    case Lexer::THEN:
    case Lexer::AS:
    case Lexer::IN:
    case Lexer::WHERE:
    case Lexer::IF:
    case Lexer::ELSE:
      return true;
    default:
      return false;
  }
}

constexpr int kAlign = -1;

// Spaces between two tokens of a line that the source separates by `gap` spaces; kAlign: keep the column.
int spacesBetween(const Token& prev, const Token& next, int gap, const OperatorRoles& roles) {
  if (next.comment()) return gap >= 2 ? kAlign : 1;
  if (prev.type == Lexer::LPAREN || prev.type == Lexer::LBRACK) return 0;
  if (next.type == Lexer::RPAREN || next.type == Lexer::RBRACK || next.type == Lexer::COMMA || next.type == Lexer::SEMI)
    return 0;
  if (prev.type == Lexer::DOT || next.type == Lexer::DOT) return 0;
  if (prev.type == Lexer::LBRACE && next.type == Lexer::RBRACE) return 0;
  if (roles.prefix.count(prev.index)) return 0;
  // Type arguments and parameters: vec<2>, set<Dip>, uniformInBox<N>(...).
  if ((next.type == Lexer::LT && roles.typeBracket(next)) || (prev.type == Lexer::LT && roles.typeBracket(prev)) ||
      (next.type == Lexer::GT && roles.typeBracket(next)))
    return 0;
  // A call, a parameter list or an index: f(x), box<N>(lo), quantity[i], f(a)[0].
  if ((next.type == Lexer::LPAREN || next.type == Lexer::LBRACK) &&
      (prev.type == Lexer::ID || prev.type == Lexer::RPAREN || prev.type == Lexer::RBRACK || roles.typeBracket(prev)))
    return 0;
  if (gap >= 2) return kAlign;
  // A length's unit: `5 cm` (a number followed by a name is nothing else in the language).
  if (prev.type == Lexer::NUMBER && next.type == Lexer::ID) return 1;
  if (roles.binary.count(prev.index) || roles.binary.count(next.index)) return 1;
  if (prev.type == Lexer::LBRACE || next.type == Lexer::LBRACE || next.type == Lexer::RBRACE ||
      prev.type == Lexer::COLON)
    return 1;
  if (prev.type == Lexer::COMMA || joinsPhrases(prev.type) || joinsPhrases(next.type)) return 1;
  return std::min(gap, 1);
}

// A bracket opened on an earlier line and not yet closed.
struct Opener {
  std::size_t type = 0;
  int lineIndent = 0;     // the indentation of the line it opened on
  bool endsLine = false;  // nothing but comments after it on its line: a block (`{`) or a broken-up list
  bool list = false;      // the `{` of an items or enum declaration: its entries end with `,`
};

class Formatter {
 public:
  Formatter(std::vector<Token> tokens, OperatorRoles roles) : tokens_(std::move(tokens)), roles_(std::move(roles)) {}

  std::string run() {
    // Logical lines: a token that starts a source line, and every token that starts where its predecessor ended.
    lineOf_.assign(tokens_.size(), 0);
    for (std::size_t i = 0; i < tokens_.size();) {
      std::size_t end = i + 1;
      while (end < tokens_.size() && tokens_[end].line == tokens_[end - 1].endLine) ++end;
      for (std::size_t k = i; k < end; ++k) lineOf_[k] = lines_.size();
      lines_.emplace_back(i, end);
      i = end;
    }
    // Alignment is kept only where it survives: a token kept in its column whose partner on the neighbouring line
    // ends up elsewhere (its own line's spacing moved it) loses its alignment, and the layout is redone. Each round
    // only removes alignments, so this ends; the result is a fixed point of formatting.
    alignAllowed_.assign(tokens_.size(), 1);
    for (;;) {
      layout();
      bool changed = false;
      for (std::size_t k = 0; k < tokens_.size(); ++k) {
        if (aligned_[k] && !tokens_[k].comment() && !partnerKeepsColumn(k)) {
          alignAllowed_[k] = 0;
          changed = true;
        }
      }
      if (!changed) return out_;
    }
  }

 private:
  void layout() {
    out_.clear();
    stack_.clear();
    statementOpen_ = false;
    statementIndent_ = statementSourceIndent_ = 0;
    statementFirst_ = 0;
    trailingComment_.reset();
    outCol_.assign(tokens_.size(), 0);
    aligned_.assign(tokens_.size(), 0);
    for (std::size_t n = 0; n < lines_.size(); ++n) {
      const auto [begin, end] = lines_[n];
      if (n > 0 && tokens_[begin].line > tokens_[lines_[n - 1].second - 1].endLine + 1) out_ += "\n";
      formatLine(n, begin, end);
    }
  }

  // Whether a token of the same type as token k, in the same source column on a neighbouring line, is in the same
  // output column as k.
  bool partnerKeepsColumn(std::size_t k) const {
    const std::size_t n = lineOf_[k];
    for (const std::size_t m : {n - 1, n + 1}) {
      if (m >= lines_.size()) continue;
      for (std::size_t j = lines_[m].first; j < lines_[m].second; ++j)
        if (tokens_[j].type == tokens_[k].type && tokens_[j].col == tokens_[k].col && outCol_[j] == outCol_[k] &&
            tokens_[j].line == tokens_[lines_[m].first].line)
          return true;
    }
    return false;
  }

  // Whether a token of type `type` starts at source column `col` on the line before or after line `n` (a table's
  // column holds tokens of one kind; another kind there is a coincidence).
  bool alignsWithNeighbour(std::size_t n, int col, std::size_t type) const {
    for (const std::size_t m : {n - 1, n + 1}) {
      if (m >= lines_.size()) continue;  // n - 1 wraps around for the first line
      for (std::size_t k = lines_[m].first; k < lines_[m].second; ++k)
        if (tokens_[k].col == col && tokens_[k].type == type && tokens_[k].line == tokens_[lines_[m].first].line)
          return true;
    }
    return false;
  }

  void formatLine(std::size_t n, std::size_t begin, std::size_t end) {
    const Token& first = tokens_[begin];
    std::size_t closers = 0;
    while (begin + closers < end && isCloser(tokens_[begin + closers].type)) ++closers;
    const Token* lastCode = nullptr;
    const Token* firstCode = nullptr;
    for (std::size_t k = begin; k < end; ++k) {
      if (tokens_[k].comment()) continue;
      if (firstCode == nullptr) firstCode = &tokens_[k];
      lastCode = &tokens_[k];
    }
    const bool continuation =
        statementOpen_ || (!stack_.empty() && !(stack_.back().type == Lexer::LBRACE && stack_.back().endsLine));
    int indent = 0;
    if (closers > 0 && !stack_.empty() && stack_.back().endsLine) {
      indent = stack_.back().lineIndent;
    } else if (continuation) {
      const int moved = first.col + (statementIndent_ - statementSourceIndent_);
      indent = moved > statementIndent_ ? moved : statementIndent_ + 4;
    } else {
      indent = 2 * static_cast<int>(std::count_if(stack_.begin(), stack_.end(), [](const Opener& o) {
                 return o.type == Lexer::LBRACE && o.endsLine;
               }));
    }
    if (lastCode == nullptr && trailingComment_ && first.col == trailingComment_->first &&
        trailingComment_->second > indent)
      indent = trailingComment_->second;

    const int shift = indent - first.col;
    std::string line(static_cast<std::size_t>(indent), ' ');
    int width = indent;
    std::vector<int> outCols;
    for (std::size_t k = begin; k < end; ++k) {
      const Token& t = tokens_[k];
      if (k > begin) {
        const Token& prev = tokens_[k - 1];
        int spaces = spacesBetween(prev, t, t.col - prev.endCol, roles_);
        // A run of spaces before code is alignment only if a neighbouring line has a token in that column; before
        // a trailing comment it always is (comment columns line up across groups of lines).
        if (spaces == kAlign && !t.comment() && (!alignAllowed_[k] || !alignsWithNeighbour(n, t.col, t.type)))
          spaces = 1;
        if (spaces == kAlign) {
          const int room = t.col + shift - width;
          aligned_[k] = room >= 2;
          spaces = room >= 2 ? room : (t.comment() ? 2 : 1);
        }
        line.append(static_cast<std::size_t>(spaces), ' ');
        width += spaces;
      }
      outCols.push_back(width);
      outCol_[k] = width;
      line += t.text;
      width = t.endLine == t.line ? width + (t.endCol - t.col) : t.endCol;
    }
    out_ += line;
    out_ += "\n";

    const Token& last = tokens_[end - 1];
    if (last.type == Lexer::LINE_COMMENT && lastCode != nullptr)
      trailingComment_ = std::make_pair(last.col, outCols.back());
    else if (lastCode != nullptr)
      trailingComment_.reset();
    if (lastCode != nullptr && !continuation) {
      statementIndent_ = indent;
      statementSourceIndent_ = first.col;
      statementFirst_ = firstCode->type;
    }
    for (std::size_t k = begin; k < end; ++k) {
      const Token& t = tokens_[k];
      if (isOpener(t.type)) {
        bool endsLine = true;
        for (std::size_t j = k + 1; j < end; ++j) endsLine = endsLine && tokens_[j].comment();
        const bool list = t.type == Lexer::LBRACE && !continuation && firstCode != nullptr &&
                          (firstCode->type == Lexer::ITEMS || firstCode->type == Lexer::ENUM);
        stack_.push_back(Opener{t.type, indent, endsLine, list});
      } else if (isCloser(t.type) && !stack_.empty()) {
        stack_.pop_back();
      }
    }
    if (lastCode != nullptr) {
      const std::size_t l = lastCode->type;
      const bool inList = !stack_.empty() && stack_.back().list;
      // A clearance's bodies are a list outside brackets: a line ending in one of its commas goes on.
      const bool clearanceBodies = stack_.empty() && statementFirst_ == Lexer::CLEARANCE;
      statementOpen_ = !(l == Lexer::SEMI || l == Lexer::LBRACE || l == Lexer::RBRACE ||
                         (l == Lexer::COMMA && (inList || (stack_.empty() && !clearanceBodies))));
    }
  }

  std::vector<Token> tokens_;
  OperatorRoles roles_;
  std::vector<std::pair<std::size_t, std::size_t>> lines_;  // logical lines: [begin, end) token ranges
  std::vector<std::size_t> lineOf_;                         // each token's logical line
  std::vector<char> alignAllowed_;                          // per token: may keep an aligned column
  std::vector<char> aligned_;                               // per token: kept its column in the last layout
  std::vector<int> outCol_;                                 // per token: output column in the last layout
  std::string out_;
  std::vector<Opener> stack_;
  bool statementOpen_ = false;      // the last code line left its statement unfinished
  int statementIndent_ = 0;         // the output indentation of the current statement's first line
  int statementSourceIndent_ = 0;   // and its indentation in the source
  std::size_t statementFirst_ = 0;  // the token type that starts the current statement
  // The trailing comment of the last code line: its source column and output column.
  std::optional<std::pair<int, int>> trailingComment_;
};

}  // namespace

std::string formatSource(std::string_view text) {
  OperatorRoles roles;
  std::vector<Token> tokens = lexAndParse(text, roles);
  std::string out = Formatter(tokens, std::move(roles)).run();
  const std::vector<Token> again = lex(out);
  const bool same = std::equal(tokens.begin(), tokens.end(), again.begin(), again.end(),
                               [](const Token& a, const Token& b) { return a.type == b.type && a.text == b.text; });
  if (!same) throw std::logic_error("cbtlc fmt changed the tokens of the file (a bug in the formatter)");
  return out;
}

}  // namespace cbtl
