// AST builder: clearances. The `clearance` declaration, the `allow` clause of an action statement and the lengths
// both take. Words with a fixed meaning here (the unit, the part, the mode) are kept as names: check-types says
// what is wrong with one, with its location, instead of the parser reporting a syntax error.
#include "compiler/ast/AstBuilderInternal.h"

#include <cstdlib>

namespace cbtl::detail {

std::unique_ptr<Decl> AstBuilder::clearance(P::ClearanceDeclContext* c) {
  auto d = start<ClearanceDecl>(c);
  d->name = ident(c->ident());
  for (auto* s : c->STRING()) {
    d->bodies.push_back(unquote(s->getText()));
    d->bodyRanges.push_back(range(s));
  }
  d->distance = length(c->lengthLit());
  return d;
}

// lengthLit : MINUS? NUMBER ident?
Length AstBuilder::length(P::LengthLitContext* ctx) {
  Length l;
  if (ctx == nullptr) return l;
  l.range = range(ctx);
  l.negative = ctx->MINUS() != nullptr;
  if (ctx->NUMBER() != nullptr) {
    l.spelling = ctx->NUMBER()->getText();
    l.value = std::strtod(l.spelling.c_str(), nullptr);
    if (l.negative) l.value = -l.value;
  }
  if (ctx->ident() != nullptr) l.unit = ident(ctx->ident());
  return l;
}

// ALLOW allowPart modeWord=ident targetExpr=expr lengthLit LBRACE actionStmt* RBRACE
std::unique_ptr<AllowClause> AstBuilder::allowClause(P::ActionAllowContext* ctx) {
  auto a = std::make_unique<AllowClause>();
  if (auto* part = ctx->allowPart(); part != nullptr) {
    if (part->ROBOT() != nullptr) {
      a->part.name = part->ROBOT()->getText();
      a->part.range = range(part->ROBOT());
    } else {
      a->part = ident(part->ident());
    }
  }
  a->mode = ident(ctx->modeWord);
  a->target = ctx->targetExpr != nullptr ? expr(ctx->targetExpr) : missing(ctx);
  a->length = length(ctx->lengthLit());
  return a;
}

}  // namespace cbtl::detail
