// AST builder: arguments, binders and expressions. Operator chains are built recursively, so nesting is
// bounded here (kMaxExprDepth) as well as by the parser's pre-scan.
#include "compiler/ast/AstBuilderInternal.h"
#include "compiler/driver/CompileLimits.h"

#include <cstdlib>

namespace cbtl::detail {
namespace {

// Expression trees deeper than this are cut (the parser's token pre-scan bounds brackets and prefix
// operators; this bounds long operator chains such as a+a+...+a).
constexpr int kMaxExprDepth = CompileLimits::kMaxExprDepth;

}  // namespace

std::vector<Arg> AstBuilder::args(P::ArgListContext* ctx) {
  std::vector<Arg> out;
  if (ctx == nullptr) return out;
  for (auto* a : ctx->arg()) {
    Arg arg;
    arg.range = range(a);
    if (a->ident() != nullptr) arg.name = ident(a->ident());
    arg.value = expr(a->expr());
    out.push_back(std::move(arg));
  }
  return out;
}

std::unique_ptr<Binder> AstBuilder::binder(P::BinderContext* ctx) {
  auto b = std::make_unique<Binder>();
  if (ctx == nullptr) return b;
  b->range = range(ctx);
  for (auto* id : ctx->ident()) {
    auto bd = std::make_unique<BinderDecl>();
    bd->name = ident(id);
    b->names.push_back(std::move(bd));
  }
  b->set = expr(ctx->expr());
  return b;
}

ExprPtr AstBuilder::make(ExprKind kind, antlr4::ParserRuleContext* ctx) {
  return std::make_unique<Expr>(kind, range(ctx));
}

ExprPtr AstBuilder::binary(BinaryOp op, P::ExprContext* ctx, P::ExprContext* lhs, P::ExprContext* rhs) {
  auto e = make(ExprKind::Binary, ctx);
  e->binaryOp = op;
  e->operands.push_back(expr(lhs));
  e->operands.push_back(expr(rhs));
  return e;
}

ExprPtr AstBuilder::missing(antlr4::ParserRuleContext* parent) {
  auto e = std::make_unique<Expr>(ExprKind::Number, range(parent));
  e->text = "<missing>";
  return e;
}

ExprPtr AstBuilder::expr(P::ExprContext* ctx) {
  if (ctx == nullptr) return missing(nullptr);
  if (depth_ >= kMaxExprDepth) {
    depthExceeded_ = true;
    if (!depthRange_.valid()) depthRange_ = range(ctx);
    return missing(ctx);
  }
  ++depth_;
  ExprPtr e = exprInner(ctx);
  --depth_;
  return e;
}

ExprPtr AstBuilder::exprInner(P::ExprContext* ctx) {
  if (auto* c = dynamic_cast<P::PrimaryExprContext*>(ctx)) return primary(c->primary());
  if (auto* c = dynamic_cast<P::MemberExprContext*>(ctx)) {
    auto e = make(ExprKind::Member, ctx);
    e->operands.push_back(expr(c->expr()));
    Ident id = ident(c->ident());
    e->text = id.name;
    e->nameRange = id.range;
    return e;
  }
  if (auto* c = dynamic_cast<P::CallExprContext*>(ctx)) {
    auto e = make(ExprKind::Call, ctx);
    e->operands.push_back(expr(c->expr()));
    if (c->argList() != nullptr) e->args = args(c->argList());
    return e;
  }
  if (auto* c = dynamic_cast<P::IndexExprContext*>(ctx)) {
    auto e = make(ExprKind::Index, ctx);
    for (auto* x : c->expr()) e->operands.push_back(expr(x));
    return e;
  }
  if (auto* c = dynamic_cast<P::PowExprContext*>(ctx)) return binary(BinaryOp::Pow, ctx, c->expr(0), c->expr(1));
  if (auto* c = dynamic_cast<P::NegExprContext*>(ctx)) {
    auto e = make(ExprKind::Unary, ctx);
    e->unaryOp = UnaryOp::Neg;
    e->operands.push_back(expr(c->expr()));
    return e;
  }
  if (auto* c = dynamic_cast<P::NotExprContext*>(ctx)) {
    auto e = make(ExprKind::Unary, ctx);
    e->unaryOp = UnaryOp::Not;
    e->operands.push_back(expr(c->expr()));
    return e;
  }
  if (auto* c = dynamic_cast<P::MulExprContext*>(ctx)) {
    const auto t = c->op->getType();
    return binary(t == P::STAR    ? BinaryOp::Mul
                  : t == P::SLASH ? BinaryOp::Div
                                  : BinaryOp::Mod,
                  ctx, c->expr(0), c->expr(1));
  }
  if (auto* c = dynamic_cast<P::AddExprContext*>(ctx)) {
    return binary(c->op->getType() == P::PLUS ? BinaryOp::Add : BinaryOp::Sub, ctx, c->expr(0), c->expr(1));
  }
  if (auto* c = dynamic_cast<P::RangeExprContext*>(ctx)) {
    auto e = make(ExprKind::Range, ctx);
    e->operands.push_back(expr(c->expr(0)));
    e->operands.push_back(expr(c->expr(1)));
    return e;
  }
  if (auto* c = dynamic_cast<P::CmpExprContext*>(ctx)) {
    return binary(comparisonOp(c->op->getType()), ctx, c->expr(0), c->expr(1));
  }
  if (auto* c = dynamic_cast<P::InExprContext*>(ctx)) {
    auto e = make(ExprKind::In, ctx);
    e->operands.push_back(expr(c->expr(0)));
    e->operands.push_back(expr(c->expr(1)));
    return e;
  }
  if (auto* c = dynamic_cast<P::AndExprContext*>(ctx)) return binary(BinaryOp::And, ctx, c->expr(0), c->expr(1));
  if (auto* c = dynamic_cast<P::OrExprContext*>(ctx)) return binary(BinaryOp::Or, ctx, c->expr(0), c->expr(1));
  if (auto* c = dynamic_cast<P::ImpliesExprContext*>(ctx))
    return binary(BinaryOp::Implies, ctx, c->expr(0), c->expr(1));
  if (auto* c = dynamic_cast<P::IffExprContext*>(ctx)) return binary(BinaryOp::Iff, ctx, c->expr(0), c->expr(1));
  if (auto* c = dynamic_cast<P::QuantExprContext*>(ctx)) return quantifier(c);
  if (auto* c = dynamic_cast<P::IfExprContext*>(ctx)) {
    auto e = make(ExprKind::If, ctx);
    for (std::size_t i = 0; i < 3; ++i) e->operands.push_back(i < c->expr().size() ? expr(c->expr(i)) : missing(ctx));
    return e;
  }
  return missing(ctx);
}

ExprPtr AstBuilder::quantifier(P::QuantExprContext* c) {
  auto e = make(ExprKind::Quantifier, c);
  e->quant = c->FORALL() != nullptr ? QuantKind::Forall : QuantKind::Exists;
  e->binder = binder(c->binder());
  const auto xs = c->expr();
  if (c->WHERE() != nullptr && xs.size() == 2) {
    e->operands.push_back(expr(xs[0]));
    e->operands.push_back(expr(xs[1]));
  } else {
    e->operands.push_back(nullptr);
    e->operands.push_back(xs.empty() ? missing(c) : expr(xs.back()));
  }
  return e;
}

BinaryOp AstBuilder::comparisonOp(std::size_t tokenType) {
  switch (tokenType) {
    case P::EQ:
      return BinaryOp::Eq;
    case P::NEQ:
      return BinaryOp::Ne;
    case P::LT:
      return BinaryOp::Lt;
    case P::LE:
      return BinaryOp::Le;
    case P::GT:
      return BinaryOp::Gt;
    default:
      return BinaryOp::Ge;
  }
}

ExprPtr AstBuilder::primary(P::PrimaryContext* ctx) {
  if (ctx == nullptr) return missing(nullptr);
  if (auto* c = dynamic_cast<P::NumberLitContext*>(ctx)) {
    auto e = make(ExprKind::Number, ctx);
    e->text = c->NUMBER()->getText();
    e->number = std::strtod(e->text.c_str(), nullptr);
    return e;
  }
  if (auto* c = dynamic_cast<P::StringLitContext*>(ctx)) {
    auto e = make(ExprKind::String, ctx);
    e->text = unquote(c->STRING()->getText());
    return e;
  }
  if (auto* c = dynamic_cast<P::BoolLitContext*>(ctx)) {
    auto e = make(ExprKind::Bool, ctx);
    e->boolean = c->TRUE() != nullptr;
    return e;
  }
  if (auto* c = dynamic_cast<P::NameRefContext*>(ctx)) {
    auto e = make(ExprKind::Name, ctx);
    e->text = ident(c->ident()).name;
    return e;
  }
  // One grammar alternative for both, so that a missing ')' is one error, not an ambiguity between the two.
  if (auto* c = dynamic_cast<P::ParenOrTupleContext*>(ctx)) {
    const auto xs = c->expr();
    if (xs.size() == 1) {
      ExprPtr inner = expr(xs.front());
      inner->range = range(ctx);  // the parentheses belong to the expression for diagnostics
      return inner;
    }
    auto e = make(ExprKind::Tuple, ctx);
    for (auto* x : xs) e->operands.push_back(expr(x));
    return e;
  }
  if (auto* c = dynamic_cast<P::ListLitContext*>(ctx)) {
    auto e = make(ExprKind::List, ctx);
    for (auto* x : c->expr()) e->operands.push_back(expr(x));
    return e;
  }
  return missing(ctx);
}

}  // namespace cbtl::detail
