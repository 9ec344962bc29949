#include "compiler/parse/SyntaxErrors.h"

#include "compiler/util/Suggest.h"

#include "grammar/CbtlParser.h"

#include <fmt/format.h>

#include <map>
#include <string>
#include <vector>

namespace cbtl {
namespace {

using cbtlgrammar::CbtlParser;

// What each grammar rule is called in messages. Rules missing here inherit their parent's name.
const std::map<std::string, std::string>& ruleDescriptions() {
  static const std::map<std::string, std::string> names = {
      {"domainDecl", "the domain header"},
      {"importDecl", "the import"},
      {"worldDecl", "the world declaration"},
      {"simulatorDecl", "the simulator declaration"},
      {"robotDecl", "the robot declaration"},
      {"clearanceDecl", "the clearance declaration"},
      {"lengthLit", "the distance"},
      {"constDecl", "the constant declaration"},
      {"enumDecl", "the enum declaration"},
      {"itemDecl", "the item type declaration"},
      {"itemsDecl", "the item set"},
      {"observeDecl", "the observation declaration"},
      {"feedbackDecl", "the feedback declaration"},
      {"funcDecl", "the function declaration"},
      {"samplerDecl", "the sampler declaration"},
      {"actionDecl", "the action declaration"},
      {"varDecl", "the variable declaration"},
      {"requireDecl", "the constraint"},
      {"sampleDecl", "the sample statement"},
      {"costDecl", "the cost"},
      {"personalDecl", "the personalized constraint generator"},
      {"personalClause", "the generator clause"},
      {"skillDecl", "the skill"},
      {"actionStmt", "the action statement"},
      {"allowPart", "the allow statement"},
      {"taskDecl", "the task"},
      {"taskItem", "the task"},
  };
  return names;
}

std::string describeContext(antlr4::Parser* parser) {
  const auto& ruleNames = parser->getRuleNames();
  for (antlr4::RuleContext* ctx = parser->getContext(); ctx != nullptr;
       ctx = dynamic_cast<antlr4::RuleContext*>(ctx->parent)) {
    auto it = ruleDescriptions().find(ruleNames[ctx->getRuleIndex()]);
    if (it != ruleDescriptions().end()) return it->second;
    if (ctx->parent == nullptr) break;
  }
  return "";
}

std::string tokenDisplay(antlr4::Parser* parser, std::size_t type) {
  switch (type) {
    case antlr4::Token::EOF:
      return "end of file";
    case CbtlParser::ID:
      return "a name";
    case CbtlParser::NUMBER:
      return "a number";
    case CbtlParser::STRING:
      return "a string";
    default:
      return parser->getVocabulary().getDisplayName(type);
  }
}

std::string foundDisplay(antlr4::Token* t) {
  if (t->getType() == antlr4::Token::EOF) return "end of file";
  std::string text = t->getText();
  if (text.size() > 24) {  // in place: GCC 12 misreads `substr(...) + "..."` as out of bounds (-Warray-bounds)
    text.resize(21);
    text += "...";
  }
  return fmt::format("'{}'", text);
}

bool isExpressionStart(const antlr4::misc::IntervalSet& set) {
  return set.contains(static_cast<std::size_t>(CbtlParser::ID)) &&
         set.contains(static_cast<std::size_t>(CbtlParser::NUMBER)) &&
         set.contains(static_cast<std::size_t>(CbtlParser::LPAREN));
}

bool isBinaryOperatorSet(const antlr4::misc::IntervalSet& set) {
  return set.contains(static_cast<std::size_t>(CbtlParser::PLUS)) &&
         set.contains(static_cast<std::size_t>(CbtlParser::AND));
}

std::string describeExpected(antlr4::Parser* parser, const antlr4::misc::IntervalSet& expected) {
  if (isExpressionStart(expected)) return "an expression";
  std::vector<std::string> names;
  for (std::size_t t : expected.toList()) {
    // Operators that may continue an expression are noise in a message about a missing delimiter.
    if (isBinaryOperatorSet(expected) && t != CbtlParser::SEMI && t != CbtlParser::COMMA && t != CbtlParser::RPAREN &&
        t != CbtlParser::RBRACK && t != CbtlParser::RBRACE && t != CbtlParser::COLON && t != CbtlParser::TILDE) {
      continue;
    }
    names.push_back(tokenDisplay(parser, t));
  }
  if (names.empty()) return "something else";
  if (names.size() == 1) return names.front();
  if (names.size() > 6) {
    names.resize(6);
    names.push_back("...");
  }
  std::string out = "one of ";
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

bool isDeclarationKeyword(std::size_t type) {
  switch (type) {
    case CbtlParser::DOMAIN:
    case CbtlParser::IMPORT:
    case CbtlParser::WORLD:
    case CbtlParser::ROBOT:
    case CbtlParser::CLEARANCE:
    case CbtlParser::CONST:
    case CbtlParser::ENUM:
    case CbtlParser::ITEM:
    case CbtlParser::ITEMS:
    case CbtlParser::OBSERVE:
    case CbtlParser::FEEDBACK:
    case CbtlParser::EXTERN:
    case CbtlParser::FN:
    case CbtlParser::VAR:
    case CbtlParser::REQUIRE:
    case CbtlParser::SAMPLE:
    case CbtlParser::MINIMIZE:
    case CbtlParser::MAXIMIZE:
    case CbtlParser::PERSONAL:
    case CbtlParser::SKILL:
    case CbtlParser::TASK:
    case CbtlParser::WHEN:
    case CbtlParser::MODEL:
    case CbtlParser::LEARN:
    case CbtlParser::ACCEPT:
    case CbtlParser::FALLBACK:
    case CbtlParser::EXPLORE:
    case CbtlParser::DO:
    case CbtlParser::RUN:
    case CbtlParser::RBRACE:
    case antlr4::Token::EOF:
      return true;
    default:
      return false;
  }
}

// The keywords among `expected`, for "did you mean the keyword ...?".
std::vector<std::string> expectedKeywords(antlr4::Parser* parser, const antlr4::misc::IntervalSet& expected) {
  std::vector<std::string> keywords;
  for (std::size_t t : expected.toList()) {
    std::string name = parser->getVocabulary().getLiteralName(t);
    if (name.size() > 2 && name.front() == '\'' && std::isalpha(static_cast<unsigned char>(name[1])))
      keywords.push_back(name.substr(1, name.size() - 2));
  }
  return keywords;
}

// Hints for the mistakes people bring from other languages and for a block left open; added to the error about
// `offending`, the token the parser could not use.
void addHints(Diagnostic& d, antlr4::Parser* parser, antlr4::Token* offending,
              const antlr4::misc::IntervalSet& expected, const SyntaxErrorStrategy::TokenRange& tokenRange) {
  auto* stream = parser->getTokenStream();
  const std::size_t type = offending->getType();
  if (type == CbtlParser::ID) {
    const std::string guess = closestMatch(offending->getText(), expectedKeywords(parser, expected));
    if (!guess.empty()) d.help(fmt::format("did you mean the keyword '{}'?", guess));
  }
  if (type == CbtlParser::ALLOW && !expected.contains(static_cast<std::size_t>(CbtlParser::ALLOW)))
    d.help("'allow' is an action statement: it goes in a skill's 'do' block, around the actions it is for");
  // The start of a distance (lengthLit) is the only place a number is expected and a name is not.
  if (expected.contains(static_cast<std::size_t>(CbtlParser::NUMBER)) &&
      expected.contains(static_cast<std::size_t>(CbtlParser::MINUS)) &&
      !expected.contains(static_cast<std::size_t>(CbtlParser::ID)))
    d.help("a distance is a number and its unit, e.g. '5 cm'");
  if (type == CbtlParser::ASSIGN && !expected.contains(static_cast<std::size_t>(CbtlParser::ASSIGN)))
    d.help("'=' only gives a declaration its value (`var x : real = 1;`); to compare, write '=='");
  if (type == CbtlParser::DOT) {
    antlr4::Token* next = stream->LT(2);
    if (next != nullptr && next->getType() == CbtlParser::NUMBER &&
        next->getStartIndex() == offending->getStopIndex() + 1)
      d.help(fmt::format("a number starts with a digit: write 0{}", offending->getText() + next->getText()));
  }
  // A declaration keyword, a '}' or the end of the file inside a block: the block's '{' was never closed.
  if (isDeclarationKeyword(type) && type != CbtlParser::RBRACE) {
    std::vector<antlr4::Token*> open;
    const std::size_t end = offending->getTokenIndex();
    for (std::size_t i = 0; i < end; ++i) {
      antlr4::Token* t = stream->get(i);
      if (t->getType() == CbtlParser::LBRACE) open.push_back(t);
      if (t->getType() == CbtlParser::RBRACE && !open.empty()) open.pop_back();
    }
    if (!open.empty() && expected.contains(static_cast<std::size_t>(CbtlParser::RBRACE)))
      d.note(fmt::format("this '{{' is never closed before {}", foundDisplay(offending)), tokenRange(open.back()));
  }
}

}  // namespace

bool SyntaxErrorStrategy::reportLexicalError(antlr4::Token* offending) {
  const SourceRange range = tokenRange_(offending);
  switch (offending->getType()) {
    case CbtlParser::UNTERMINATED_STRING:
      diags_.error("E0103", range, "unterminated string: no closing '\"' on this line")
          .help("close the string on the same line; write \\\" for a quote inside it");
      return true;
    case CbtlParser::UNTERMINATED_COMMENT:
      diags_.error("E0104", SourceRange{range.file, range.begin, range.begin + 2}, "this block comment is never closed")
          .help("add '*/' where the comment ends");
      return true;
    case CbtlParser::ERROR_CHAR: {
      std::string text = offending->getText();
      Diagnostic& d = diags_.error("E0105", range, fmt::format("invalid character '{}' in the source", text));
      const std::string_view source = sources_.file(range.file).text;
      const char next = range.end < source.size() ? source[range.end] : '\0';
      if (text == "&") d.help(next == '&' ? "'&&' is written 'and' in .cbtl" : "conjunction is written 'and' in .cbtl");
      if (text == "|") d.help(next == '|' ? "'||' is written 'or' in .cbtl" : "disjunction is written 'or' in .cbtl");
      if (text == "!") d.help("negation is written 'not' in .cbtl ('!=' compares)");
      return true;
    }
    default:
      return false;
  }
}

void SyntaxErrorStrategy::reportUnexpected(antlr4::Parser* parser, antlr4::Token* offending,
                                           const antlr4::misc::IntervalSet& expected) {
  ++reported_;
  if (reportLexicalError(offending)) return;
  const std::string where = describeContext(parser);
  auto* stream = parser->getTokenStream();
  antlr4::Token* previous = stream->index() > 0 ? stream->LT(-1) : nullptr;

  // A missing ';' is the most common mistake; point at the end of the statement that lacks it.
  if (expected.contains(static_cast<std::size_t>(CbtlParser::SEMI)) && previous != nullptr &&
      (isDeclarationKeyword(offending->getType()) || offending->getLine() > previous->getLine())) {
    const SourceRange prev = tokenRange_(previous);
    diags_.error("E0102", sources_.insertionPoint(prev.file, prev.end),
                 fmt::format("expected ';' after {}", where.empty() ? "this declaration" : where));
    return;
  }

  std::string message =
      fmt::format("expected {}, found {}", describeExpected(parser, expected), foundDisplay(offending));
  if (!where.empty()) message += " in " + where;
  Diagnostic& d = diags_.error("E0101", tokenRange_(offending), message);
  addHints(d, parser, offending, expected, tokenRange_);
}

void SyntaxErrorStrategy::reportNoViableAlternative(antlr4::Parser* parser, const antlr4::NoViableAltException& e) {
  reportUnexpected(parser, e.getOffendingToken(), e.getExpectedTokens());
}

void SyntaxErrorStrategy::reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) {
  reportUnexpected(parser, e.getOffendingToken(), e.getExpectedTokens());
}

void SyntaxErrorStrategy::reportFailedPredicate(antlr4::Parser* parser, const antlr4::FailedPredicateException& e) {
  reportUnexpected(parser, e.getOffendingToken(), e.getExpectedTokens());
}

void SyntaxErrorStrategy::reportUnwantedToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  ++reported_;
  antlr4::Token* t = parser->getCurrentToken();
  if (reportLexicalError(t)) return;
  const std::string where = describeContext(parser);
  std::string message = fmt::format("unexpected {}", foundDisplay(t));
  if (!where.empty()) message += " in " + where;
  const antlr4::misc::IntervalSet expected = getExpectedTokens(parser);
  Diagnostic& d = diags_.error("E0106", tokenRange_(t), message);
  d.help(fmt::format("expected {} here", describeExpected(parser, expected)));
  addHints(d, parser, t, expected, tokenRange_);
}

void SyntaxErrorStrategy::reportMissingToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  ++reported_;
  antlr4::Token* t = parser->getCurrentToken();
  if (reportLexicalError(t)) return;
  const antlr4::misc::IntervalSet expected = getExpectedTokens(parser);
  const std::string where = describeContext(parser);
  auto* stream = parser->getTokenStream();
  antlr4::Token* previous = stream->index() > 0 ? stream->LT(-1) : nullptr;
  const std::string what = describeExpected(parser, expected);
  if (previous != nullptr) {
    const SourceRange prev = tokenRange_(previous);
    diags_.error(
        "E0102", sources_.insertionPoint(prev.file, prev.end),
        fmt::format("expected {} after {}", what, where.empty() ? fmt::format("'{}'", previous->getText()) : where));
  } else {
    diags_.error("E0102", tokenRange_(t), fmt::format("expected {} before {}", what, foundDisplay(t)));
  }
}

}  // namespace cbtl
