// The AST builder's entry point, the module, and the small pieces every part uses: source ranges,
// identifiers, string literals and types as written. Declarations and expressions are built in
// AstBuilderDecls.cpp and AstBuilderExprs.cpp (see AstBuilderInternal.h).
#include "compiler/ast/AstBuilder.h"

#include "compiler/ast/AstBuilderInternal.h"

#include <cstdlib>

namespace cbtl {

std::unique_ptr<Module> buildAst(void* fileContext, FileId file, const TokenRangeFn& tokenRange, bool* depthExceeded,
                                 SourceRange* depthRange) {
  detail::AstBuilder builder(file, tokenRange);
  auto module = builder.build(static_cast<detail::AstBuilder::P::FileContext*>(fileContext));
  if (depthExceeded != nullptr) *depthExceeded = builder.depthExceeded();
  if (depthRange != nullptr) *depthRange = builder.depthRange();
  return module;
}

namespace detail {

std::unique_ptr<Module> AstBuilder::build(P::FileContext* ctx) {
  auto module = std::make_unique<Module>();
  module->file = file_;
  if (ctx == nullptr) return module;
  if (auto* d = ctx->domainDecl(); d != nullptr && d->qualifiedName() != nullptr) {
    auto decl = std::make_unique<DomainDecl>();
    decl->range = range(d);
    decl->name = qualified(d->qualifiedName());
    module->domainName = decl->name.name;
    module->decls.push_back(std::move(decl));
  }
  for (auto* top : ctx->topDecl()) {
    if (auto decl = topDecl(top)) module->decls.push_back(std::move(decl));
  }
  return module;
}

SourceRange AstBuilder::range(antlr4::ParserRuleContext* ctx) const {
  if (ctx == nullptr || ctx->getStart() == nullptr) return SourceRange{file_, 0, 0};
  SourceRange a = tokenRange_(ctx->getStart());
  antlr4::Token* stop = ctx->getStop();
  // An empty rule (error recovery) has stop before start.
  if (stop == nullptr || stop->getTokenIndex() < ctx->getStart()->getTokenIndex())
    return SourceRange{file_, a.begin, a.begin};
  return a.to(tokenRange_(stop));
}

SourceRange AstBuilder::range(antlr4::tree::TerminalNode* node) const {
  return node == nullptr ? SourceRange{file_, 0, 0} : tokenRange_(node->getSymbol());
}

Ident AstBuilder::ident(P::IdentContext* ctx) const {
  Ident id;
  if (ctx == nullptr || ctx->ID() == nullptr) return id;
  id.name = ctx->ID()->getText();
  id.range = range(ctx);
  // Error recovery may conjure a missing ID whose text is "<missing ID>".
  if (id.name.rfind("<missing", 0) == 0) id.name.clear();
  return id;
}

Ident AstBuilder::qualified(P::QualifiedNameContext* ctx) const {
  Ident id;
  if (ctx == nullptr) return id;
  for (std::size_t i = 0; i < ctx->ident().size(); ++i) {
    if (i) id.name += '.';
    id.name += ident(ctx->ident(i)).name;
  }
  id.range = range(ctx);
  return id;
}

std::string AstBuilder::unquote(const std::string& raw) {
  std::string out;
  if (raw.size() < 2) return out;
  for (std::size_t i = 1; i + 1 < raw.size(); ++i) {
    if (raw[i] == '\\' && i + 2 < raw.size()) {
      const char c = raw[++i];
      switch (c) {
        case 'n':
          out += '\n';
          break;
        case 't':
          out += '\t';
          break;
        default:
          out += c;
          break;
      }
    } else {
      out += raw[i];
    }
  }
  return out;
}

// typeRef : ident (LT typeArg (COMMA typeArg)* GT)?
TypeRef AstBuilder::typeRef(P::TypeRefContext* ctx) {
  TypeRef t;
  if (ctx == nullptr) return t;
  t.name = ident(ctx->ident());
  t.range = range(ctx);
  for (auto* a : ctx->typeArg()) {
    TypeRef::Arg arg;
    arg.range = range(a);
    if (a->NUMBER() != nullptr) {
      arg.isNumber = true;
      arg.number = std::strtod(a->NUMBER()->getText().c_str(), nullptr);
    } else {
      arg.type = std::make_unique<TypeRef>(typeRef(a->typeRef()));
    }
    t.args.push_back(std::move(arg));
  }
  return t;
}

std::vector<Param> AstBuilder::params(P::ParamListContext* ctx) {
  std::vector<Param> out;
  if (ctx == nullptr) return out;
  for (auto* p : ctx->param()) out.push_back(Param{ident(p->ident()), typeRef(p->typeRef())});
  return out;
}

std::unique_ptr<IndexSpec> AstBuilder::indexSpec(P::IndexSpecContext* ctx) {
  if (ctx == nullptr) return nullptr;
  auto spec = std::make_unique<IndexSpec>();
  spec->range = range(ctx);
  if (ctx->ident() != nullptr) spec->binder = ident(ctx->ident());
  spec->set = expr(ctx->expr());
  return spec;
}

std::vector<FieldInit> AstBuilder::fieldInits(const std::vector<P::FieldInitContext*>& inits) {
  std::vector<FieldInit> out;
  for (auto* f : inits) out.push_back(FieldInit{ident(f->ident()), expr(f->expr())});
  return out;
}

}  // namespace detail
}  // namespace cbtl
