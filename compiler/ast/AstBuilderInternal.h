// AstBuilderInternal.h — the AST builder, shared by its implementation files only.
//
// Internal to compiler/ast: callers use buildAst() (AstBuilder.h), and only the builder's .cpp files see
// the generated parser headers included here. The builder is one class because every part needs the file
// id, the token-range callback and the expression depth guard, and declarations and expressions build
// each other. Its member functions are implemented by concern:
//   AstBuilder.cpp       the entry point, the module, source ranges, identifiers, strings and types
//   AstBuilderDecls.cpp  top-level declarations, scope statements, generators, skills, actions and tasks
//   AstBuilderClearances.cpp  clearance declarations, allow clauses and lengths
//   AstBuilderExprs.cpp  arguments, binders and expressions (with the nesting limit)
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/ast/AstBuilder.h"
#include "grammar/CbtlParser.h"

#include <antlr4-runtime.h>

#include <memory>
#include <string>
#include <vector>

namespace cbtl::detail {

class AstBuilder {
 public:
  using P = cbtlgrammar::CbtlParser;

  AstBuilder(FileId file, const TokenRangeFn& tokenRange) : file_(file), tokenRange_(tokenRange) {}

  // The module of one parse tree; a null tree gives an empty module.
  std::unique_ptr<Module> build(P::FileContext* ctx);

  // True if an expression was nested past the limit and cut; depthRange() is where the first cut began.
  bool depthExceeded() const { return depthExceeded_; }
  SourceRange depthRange() const { return depthRange_; }

 private:
  // --- AstBuilder.cpp: source ranges, names, strings and types ---
  SourceRange range(antlr4::ParserRuleContext* ctx) const;
  SourceRange range(antlr4::tree::TerminalNode* node) const;
  // An identifier; its name is empty where error recovery left none.
  Ident ident(P::IdentContext* ctx) const;
  Ident qualified(P::QualifiedNameContext* ctx) const;
  // The contents of a string literal with its escapes (\n, \t, \x for any other x) decoded.
  static std::string unquote(const std::string& raw);

  // A new declaration node spanning `ctx`.
  template <typename D>
  std::unique_ptr<D> start(antlr4::ParserRuleContext* ctx) {
    auto d = std::make_unique<D>();
    d->range = range(ctx);
    return d;
  }

  TypeRef typeRef(P::TypeRefContext* ctx);
  std::vector<Param> params(P::ParamListContext* ctx);
  std::unique_ptr<IndexSpec> indexSpec(P::IndexSpecContext* ctx);
  std::vector<FieldInit> fieldInits(const std::vector<P::FieldInitContext*>& inits);

  // --- AstBuilderDecls.cpp: declarations ---
  std::unique_ptr<Decl> topDecl(P::TopDeclContext* ctx);
  std::unique_ptr<Decl> importDecl(P::ImportDeclContext* c);
  // const, enum, item, items, observe and feedback declarations; null if `ctx` is none of them.
  std::unique_ptr<Decl> dataDecl(P::TopDeclContext* ctx);
  // fn, extern sampler and extern action declarations; null if `ctx` is none of them.
  std::unique_ptr<Decl> callableDecl(P::TopDeclContext* ctx);
  void callable(CallableDecl& d, P::IdentContext* name, P::TypeParamsContext* tps, P::ParamListContext* ps,
                P::TypeRefContext* result);
  std::unique_ptr<Decl> scopeStmt(P::ScopeStmtContext* ctx);
  std::unique_ptr<Decl> personal(P::PersonalDeclContext* ctx);
  PerKey perKey(P::ExprContext* ctx);
  std::unique_ptr<ActionStmt> actionStmt(P::ActionStmtContext* ctx);
  std::unique_ptr<Decl> skill(P::SkillDeclContext* ctx);
  SkillInstance skillInstance(P::SkillInstanceContext* ctx);
  std::unique_ptr<Decl> task(P::TaskDeclContext* ctx);

  // --- AstBuilderClearances.cpp: clearances ---
  std::unique_ptr<Decl> clearance(P::ClearanceDeclContext* c);
  Length length(P::LengthLitContext* ctx);
  // The part, the mode, the target and the distance of an allow statement (its body is built by actionStmt).
  std::unique_ptr<AllowClause> allowClause(P::ActionAllowContext* ctx);

  // --- AstBuilderExprs.cpp: expressions ---
  std::vector<Arg> args(P::ArgListContext* ctx);
  std::unique_ptr<Binder> binder(P::BinderContext* ctx);
  ExprPtr make(ExprKind kind, antlr4::ParserRuleContext* ctx);
  ExprPtr binary(BinaryOp op, P::ExprContext* ctx, P::ExprContext* lhs, P::ExprContext* rhs);
  // Returns a placeholder for parts that error recovery removed, so later passes never see null operands
  // where the grammar promises one.
  ExprPtr missing(antlr4::ParserRuleContext* parent);
  // An expression, or a placeholder once nesting passes the limit (which sets depthExceeded()).
  ExprPtr expr(P::ExprContext* ctx);
  ExprPtr exprInner(P::ExprContext* ctx);
  ExprPtr quantifier(P::QuantExprContext* ctx);
  ExprPtr primary(P::PrimaryContext* ctx);
  // The operator of a comparison token (EQ, NEQ, LT, LE, GT; anything else is GE).
  static BinaryOp comparisonOp(std::size_t tokenType);

  FileId file_;
  const TokenRangeFn& tokenRange_;
  int depth_ = 0;
  bool depthExceeded_ = false;
  SourceRange depthRange_;
};

}  // namespace cbtl::detail
