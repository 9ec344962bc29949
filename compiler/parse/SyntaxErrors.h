// SyntaxErrors.h — the ANTLR error strategy that turns parser errors into friendly diagnostics.
//
// It keeps ANTLR's recovery (single-token insertion/deletion, resynchronisation) and replaces only the
// messages: "expected ';' after the variable declaration" instead of "mismatched input 'var' expecting
// {...}", keyword suggestions for misspelt keywords, and specific codes for unterminated strings and
// comments and for stray characters.
#pragma once

#include "compiler/diag/DiagnosticEngine.h"

#include <antlr4-runtime.h>

#include <functional>

namespace cbtl {

class SyntaxErrorStrategy : public antlr4::DefaultErrorStrategy {
 public:
  // Maps an ANTLR token to the byte range it covers in the source file.
  using TokenRange = std::function<SourceRange(antlr4::Token*)>;

  // `sources` gives one-byte spans for insertion points (a missing token after the previous one).
  SyntaxErrorStrategy(DiagnosticEngine& diags, TokenRange tokenRange, const SourceManager& sources)
      : diags_(diags), tokenRange_(std::move(tokenRange)), sources_(sources) {}

  std::size_t errorsReported() const { return reported_; }

 protected:
  void reportNoViableAlternative(antlr4::Parser* parser, const antlr4::NoViableAltException& e) override;
  void reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) override;
  void reportFailedPredicate(antlr4::Parser* parser, const antlr4::FailedPredicateException& e) override;
  void reportUnwantedToken(antlr4::Parser* parser) override;
  void reportMissingToken(antlr4::Parser* parser) override;

 private:
  void reportUnexpected(antlr4::Parser* parser, antlr4::Token* offending, const antlr4::misc::IntervalSet& expected);
  bool reportLexicalError(antlr4::Token* offending);

  DiagnosticEngine& diags_;
  TokenRange tokenRange_;
  const SourceManager& sources_;
  std::size_t reported_ = 0;
};

}  // namespace cbtl
