#include "compiler/ast/AstBuilder.h"

#include "grammar/CbtlParser.h"

#include <antlr4-runtime.h>

#include <cstdlib>

namespace cbtl {
namespace {

using P = cbtlgrammar::CbtlParser;

// Expression trees deeper than this are cut (the parser's token pre-scan bounds brackets and prefix
// operators; this bounds long operator chains such as a+a+...+a).
constexpr int kMaxExprDepth = 1000;

class Builder {
 public:
  Builder(FileId file, const TokenRangeFn& tokenRange) : file_(file), tokenRange_(tokenRange) {}

  std::unique_ptr<Module> build(P::FileContext* ctx) {
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

  bool depthExceeded() const { return depthExceeded_; }

 private:
  // --- helpers ---------------------------------------------------------------------------------

  SourceRange range(antlr4::ParserRuleContext* ctx) const {
    if (ctx == nullptr || ctx->getStart() == nullptr) return SourceRange{file_, 0, 0};
    SourceRange a = tokenRange_(ctx->getStart());
    antlr4::Token* stop = ctx->getStop();
    // An empty rule (error recovery) has stop before start.
    if (stop == nullptr || stop->getTokenIndex() < ctx->getStart()->getTokenIndex())
      return SourceRange{file_, a.begin, a.begin};
    return a.to(tokenRange_(stop));
  }
  SourceRange range(antlr4::tree::TerminalNode* node) const {
    return node == nullptr ? SourceRange{file_, 0, 0} : tokenRange_(node->getSymbol());
  }

  Ident ident(P::IdentContext* ctx) const {
    Ident id;
    if (ctx == nullptr || ctx->ID() == nullptr) return id;
    id.name = ctx->ID()->getText();
    id.range = range(ctx);
    // Error recovery may conjure a missing ID whose text is "<missing ID>".
    if (id.name.rfind("<missing", 0) == 0) id.name.clear();
    return id;
  }

  Ident qualified(P::QualifiedNameContext* ctx) const {
    Ident id;
    if (ctx == nullptr) return id;
    for (std::size_t i = 0; i < ctx->ident().size(); ++i) {
      if (i) id.name += '.';
      id.name += ident(ctx->ident(i)).name;
    }
    id.range = range(ctx);
    return id;
  }

  static std::string unquote(const std::string& raw) {
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

  template <typename D>
  std::unique_ptr<D> start(antlr4::ParserRuleContext* ctx) {
    auto d = std::make_unique<D>();
    d->range = range(ctx);
    return d;
  }

  // --- types ---------------------------------------------------------------------------------

  // typeRef : ident (LT typeArg (COMMA typeArg)* GT)?
  TypeRef typeRef(P::TypeRefContext* ctx) {
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

  std::vector<Param> params(P::ParamListContext* ctx) {
    std::vector<Param> out;
    if (ctx == nullptr) return out;
    for (auto* p : ctx->param()) out.push_back(Param{ident(p->ident()), typeRef(p->typeRef())});
    return out;
  }

  std::unique_ptr<IndexSpec> indexSpec(P::IndexSpecContext* ctx) {
    if (ctx == nullptr) return nullptr;
    auto spec = std::make_unique<IndexSpec>();
    spec->range = range(ctx);
    if (ctx->ident() != nullptr) spec->binder = ident(ctx->ident());
    spec->set = expr(ctx->expr());
    return spec;
  }

  std::vector<FieldInit> fieldInits(const std::vector<P::FieldInitContext*>& inits) {
    std::vector<FieldInit> out;
    for (auto* f : inits) out.push_back(FieldInit{ident(f->ident()), expr(f->expr())});
    return out;
  }

  // --- declarations ----------------------------------------------------------------------------

  std::unique_ptr<Decl> topDecl(P::TopDeclContext* ctx) {
    if (auto* c = ctx->domainDecl()) {  // a misplaced or repeated header; name resolution reports it (E0211)
      auto d = start<DomainDecl>(c);
      if (c->qualifiedName() != nullptr) d->name = qualified(c->qualifiedName());
      return d;
    }
    if (auto* c = ctx->importDecl()) {
      auto d = start<ImportDecl>(c);
      if (c->STRING() != nullptr) {
        d->isPath = true;
        d->target = unquote(c->STRING()->getText());
        d->targetRange = range(c->STRING());
      } else if (c->qualifiedName() != nullptr) {
        d->target = qualified(c->qualifiedName()).name;
        d->targetRange = range(c->qualifiedName());
      }
      return d;
    }
    if (auto* c = ctx->worldDecl()) {
      auto d = start<WorldDecl>(c);
      if (c->STRING() != nullptr) d->path = unquote(c->STRING()->getText());
      return d;
    }
    if (auto* c = ctx->robotDecl()) {
      auto d = start<RobotDecl>(c);
      d->name = ident(c->ident());
      d->fields = fieldInits(c->fieldInit());
      return d;
    }
    if (auto* c = ctx->constDecl()) {
      auto d = start<ConstDecl>(c);
      d->name = ident(c->ident());
      d->index = indexSpec(c->indexSpec());
      if (c->typeRef() != nullptr) d->type = std::make_unique<TypeRef>(typeRef(c->typeRef()));
      d->value = expr(c->expr());
      return d;
    }
    if (auto* c = ctx->enumDecl()) {
      auto d = start<EnumDecl>(c);
      const auto ids = c->ident();
      if (!ids.empty()) d->name = ident(ids[0]);
      for (std::size_t i = 1; i < ids.size(); ++i) d->members.push_back(ident(ids[i]));
      return d;
    }
    if (auto* c = ctx->itemDecl()) {
      auto d = start<ItemTypeDecl>(c);
      d->name = ident(c->ident());
      for (auto* f : c->fieldDecl()) d->fields.push_back(Param{ident(f->ident()), typeRef(f->typeRef())});
      return d;
    }
    if (auto* c = ctx->itemsDecl()) {
      auto d = start<ItemsDecl>(c);
      d->name = ident(c->ident());
      d->itemType = typeRef(c->typeRef());
      for (auto* e : c->itemEntry()) {
        ItemEntry entry;
        entry.name = ident(e->ident());
        entry.range = range(e);
        entry.fields = fieldInits(e->fieldInit());
        d->entries.push_back(std::move(entry));
      }
      return d;
    }
    if (auto* c = ctx->observeDecl()) {
      auto d = start<ObserveDecl>(c);
      d->name = ident(c->ident());
      d->index = indexSpec(c->indexSpec());
      d->type = typeRef(c->typeRef());
      return d;
    }
    if (auto* c = ctx->feedbackDecl()) {
      auto d = start<FeedbackDecl>(c);
      d->name = ident(c->ident());
      d->params = params(c->paramList());
      return d;
    }
    if (auto* c = ctx->funcDecl()) {
      auto d = start<FuncDecl>(c);
      d->isExtern = c->EXTERN() != nullptr;
      callable(*d, c->ident(), c->typeParams(), c->paramList(), c->typeRef());
      if (c->expr() != nullptr) d->body = expr(c->expr());
      return d;
    }
    if (auto* c = ctx->samplerDecl()) {
      auto d = start<SamplerDecl>(c);
      d->isExtern = true;
      callable(*d, c->ident(), c->typeParams(), c->paramList(), c->typeRef());
      return d;
    }
    if (auto* c = ctx->actionDecl()) {
      auto d = start<ActionDecl>(c);
      d->isExtern = true;
      callable(*d, c->ident(), c->typeParams(), c->paramList(), nullptr);
      return d;
    }
    if (auto* c = ctx->personalDecl()) return personal(c);
    if (auto* c = ctx->skillDecl()) return skill(c);
    if (auto* c = ctx->taskDecl()) return task(c);
    if (auto* c = ctx->scopeStmt()) return scopeStmt(c);
    return nullptr;
  }

  void callable(CallableDecl& d, P::IdentContext* name, P::TypeParamsContext* tps, P::ParamListContext* ps,
                P::TypeRefContext* result) {
    d.name = ident(name);
    if (tps != nullptr) {
      for (auto* id : tps->ident()) d.typeParams.push_back(ident(id));
    }
    d.params = params(ps);
    if (result != nullptr) d.result = std::make_unique<TypeRef>(typeRef(result));
  }

  std::unique_ptr<Decl> scopeStmt(P::ScopeStmtContext* ctx) {
    if (auto* c = ctx->varDecl()) {
      auto d = start<VarDecl>(c);
      d->name = ident(c->ident());
      d->index = indexSpec(c->indexSpec());
      d->type = typeRef(c->typeRef());
      // `in` comes before `=`: the first expr is the domain when IN is present.
      const auto exprs = c->expr();
      std::size_t next = 0;
      if (c->IN() != nullptr && next < exprs.size()) d->domain = expr(exprs[next++]);
      if (c->ASSIGN() != nullptr && next < exprs.size()) d->init = expr(exprs[next++]);
      return d;
    }
    if (auto* c = ctx->requireDecl()) {
      auto d = start<RequireDecl>(c);
      if (c->ident() != nullptr) d->name = ident(c->ident());
      d->condition = expr(c->expr());
      return d;
    }
    if (auto* c = ctx->sampleDecl()) {
      auto d = start<SampleDecl>(c);
      for (auto* e : c->expr()) d->targets.push_back(expr(e));
      d->sampler = ident(c->ident());
      d->hasArgs = c->LPAREN() != nullptr;
      if (c->argList() != nullptr) d->args = args(c->argList());
      if (c->binder() != nullptr) d->forBinder = binder(c->binder());
      return d;
    }
    if (auto* c = ctx->costDecl()) {
      auto d = start<CostDecl>(c);
      d->maximize = c->MAXIMIZE() != nullptr;
      d->value = expr(c->expr());
      return d;
    }
    return nullptr;
  }

  std::unique_ptr<Decl> personal(P::PersonalDeclContext* ctx) {
    auto d = start<PersonalDecl>(ctx);
    d->name = ident(ctx->ident());
    d->params = params(ctx->paramList());
    for (auto* clause : ctx->personalClause()) {
      if (auto* w = dynamic_cast<P::WhenClauseContext*>(clause)) {
        d->whenRanges.push_back(range(w));
        for (auto* pc : w->patternClause()) {
          PatternClause p;
          p.param = ident(pc->ident());
          p.kind = pc->REGEX() != nullptr ? PatternKind::Regex : PatternKind::Glob;
          if (pc->STRING() != nullptr) {
            p.pattern = unquote(pc->STRING()->getText());
            p.patternRange = range(pc->STRING());
          }
          d->patterns.push_back(std::move(p));
        }
      } else if (auto* m = dynamic_cast<P::ModelClauseContext*>(clause)) {
        d->modelRanges.push_back(range(m));
        for (auto* f : m->modelFactor()) {
          ModelFactor factor;
          factor.range = range(f);
          const auto ids = f->ident();
          if (f->ASSIGN() != nullptr && ids.size() >= 2) {
            factor.label = ident(ids[0]);
            factor.kind = ident(ids[1]);
          } else if (!ids.empty()) {
            factor.kind = ident(ids[0]);
          }
          if (f->argList() != nullptr) factor.args = args(f->argList());
          d->factors.push_back(std::move(factor));
        }
        for (auto* k : m->ident()) d->perKeys.push_back(ident(k));
      } else if (auto* a = dynamic_cast<P::AcceptClauseContext*>(clause)) {
        d->accepts.push_back(expr(a->expr()));
      } else if (auto* fb = dynamic_cast<P::FallbackClauseContext*>(clause)) {
        d->fallbacks.push_back(expr(fb->expr()));
      } else if (auto* gc = dynamic_cast<P::GuardClauseContext*>(clause)) {
        d->guards.push_back(expr(gc->expr()));
      } else if (auto* l = dynamic_cast<P::LearnClauseContext*>(clause)) {
        LearnRule rule;
        rule.range = range(l);
        rule.event = ident(l->ident());
        for (auto* b : l->learnBinder()) {
          auto bd = std::make_unique<BinderDecl>();
          if (b->ident() != nullptr)
            bd->name = ident(b->ident());
          else
            bd->name.range = range(b);
          rule.binderRanges.push_back(range(b));
          rule.binders.push_back(std::move(bd));
        }
        for (auto* li : l->labelItem()) {
          LearnLabel label;
          if (li->ident() != nullptr) label.factor = ident(li->ident());
          label.value = expr(li->expr());
          rule.labels.push_back(std::move(label));
        }
        if (l->IF() != nullptr) rule.condition = expr(l->expr());
        d->learnRules.push_back(std::move(rule));
      }
    }
    return d;
  }

  std::unique_ptr<ActionStmt> actionStmt(P::ActionStmtContext* ctx) {
    auto s = std::make_unique<ActionStmt>();
    s->range = range(ctx);
    if (auto* c = dynamic_cast<P::ActionCallContext*>(ctx)) {
      s->kind = ActionStmtKind::Call;
      s->callee = ident(c->ident());
      if (c->argList() != nullptr) s->args = args(c->argList());
    } else if (auto* f = dynamic_cast<P::ActionForContext*>(ctx)) {
      s->kind = ActionStmtKind::For;
      s->forBinder = binder(f->binder());
      for (auto* b : f->actionStmt()) s->body.push_back(actionStmt(b));
    } else if (auto* i = dynamic_cast<P::ActionIfContext*>(ctx)) {
      s->kind = ActionStmtKind::If;
      s->condition = expr(i->expr());
      // actionStmt() lists the then-branch and else-branch statements together; split at ELSE.
      const std::size_t elseAt = i->ELSE() != nullptr ? i->ELSE()->getSymbol()->getTokenIndex() : SIZE_MAX;
      s->hasElse = i->ELSE() != nullptr;
      for (auto* b : i->actionStmt()) {
        auto stmt = actionStmt(b);
        if (b->getStart()->getTokenIndex() > elseAt)
          s->elseBody.push_back(std::move(stmt));
        else
          s->body.push_back(std::move(stmt));
      }
    } else if (auto* bl = dynamic_cast<P::ActionBlockContext*>(ctx)) {
      s->kind = ActionStmtKind::Block;
      for (auto* b : bl->actionStmt()) s->body.push_back(actionStmt(b));
    }
    return s;
  }

  std::unique_ptr<Decl> skill(P::SkillDeclContext* ctx) {
    auto d = start<SkillDecl>(ctx);
    d->name = ident(ctx->ident());
    d->params = params(ctx->paramList());
    for (auto* item : ctx->skillItem()) {
      if (item->scopeStmt() != nullptr) {
        if (auto s = scopeStmt(item->scopeStmt())) d->body.push_back(std::move(s));
      } else if (item->doStmt() != nullptr && item->doStmt()->actionStmt() != nullptr) {
        d->actions.push_back(actionStmt(item->doStmt()->actionStmt()));
      }
    }
    return d;
  }

  SkillInstance skillInstance(P::SkillInstanceContext* ctx) {
    SkillInstance inst;
    inst.range = range(ctx);
    const auto ids = ctx->ident();
    if (!ids.empty()) inst.skill = ident(ids[0]);
    if (ctx->AS() != nullptr && ids.size() >= 2) inst.alias = ident(ids[1]);
    inst.hasArgs = ctx->LPAREN() != nullptr;
    if (ctx->argList() != nullptr) inst.args = args(ctx->argList());
    return inst;
  }

  std::unique_ptr<Decl> task(P::TaskDeclContext* ctx) {
    auto d = start<TaskDecl>(ctx);
    if (auto* s = dynamic_cast<P::TaskShortContext*>(ctx)) {
      d->name = ident(s->ident());
      for (auto* inst : s->skillInstance()) d->instances.push_back(skillInstance(inst));
    } else if (auto* b = dynamic_cast<P::TaskBlockContext*>(ctx)) {
      d->name = ident(b->ident());
      for (auto* item : b->taskItem()) {
        if (item->scopeStmt() != nullptr) {
          if (auto stmt = scopeStmt(item->scopeStmt())) d->body.push_back(std::move(stmt));
        } else {
          for (auto* inst : item->skillInstance()) d->instances.push_back(skillInstance(inst));
        }
      }
    }
    return d;
  }

  // --- expressions ---------------------------------------------------------------------------

  std::vector<Arg> args(P::ArgListContext* ctx) {
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

  std::unique_ptr<Binder> binder(P::BinderContext* ctx) {
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

  ExprPtr make(ExprKind kind, antlr4::ParserRuleContext* ctx) { return std::make_unique<Expr>(kind, range(ctx)); }

  ExprPtr binary(BinaryOp op, P::ExprContext* ctx, P::ExprContext* lhs, P::ExprContext* rhs) {
    auto e = make(ExprKind::Binary, ctx);
    e->binaryOp = op;
    e->operands.push_back(expr(lhs));
    e->operands.push_back(expr(rhs));
    return e;
  }

  // Returns a placeholder for parts that error recovery removed, so later passes never see null operands
  // where the grammar promises one.
  ExprPtr missing(antlr4::ParserRuleContext* parent) {
    auto e = std::make_unique<Expr>(ExprKind::Number, range(parent));
    e->text = "<missing>";
    return e;
  }

  ExprPtr expr(P::ExprContext* ctx) {
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

  ExprPtr exprInner(P::ExprContext* ctx) {
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
      BinaryOp op = BinaryOp::Eq;
      switch (c->op->getType()) {
        case P::EQ:
          op = BinaryOp::Eq;
          break;
        case P::NEQ:
          op = BinaryOp::Ne;
          break;
        case P::LT:
          op = BinaryOp::Lt;
          break;
        case P::LE:
          op = BinaryOp::Le;
          break;
        case P::GT:
          op = BinaryOp::Gt;
          break;
        default:
          op = BinaryOp::Ge;
          break;
      }
      return binary(op, ctx, c->expr(0), c->expr(1));
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
    if (auto* c = dynamic_cast<P::QuantExprContext*>(ctx)) {
      auto e = make(ExprKind::Quantifier, ctx);
      e->quant = c->FORALL() != nullptr ? QuantKind::Forall : QuantKind::Exists;
      e->binder = binder(c->binder());
      const auto xs = c->expr();
      if (c->WHERE() != nullptr && xs.size() == 2) {
        e->operands.push_back(expr(xs[0]));
        e->operands.push_back(expr(xs[1]));
      } else {
        e->operands.push_back(nullptr);
        e->operands.push_back(xs.empty() ? missing(ctx) : expr(xs.back()));
      }
      return e;
    }
    if (auto* c = dynamic_cast<P::IfExprContext*>(ctx)) {
      auto e = make(ExprKind::If, ctx);
      for (std::size_t i = 0; i < 3; ++i) e->operands.push_back(i < c->expr().size() ? expr(c->expr(i)) : missing(ctx));
      return e;
    }
    return missing(ctx);
  }

  ExprPtr primary(P::PrimaryContext* ctx) {
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

  FileId file_;
  const TokenRangeFn& tokenRange_;
  int depth_ = 0;
  bool depthExceeded_ = false;
  SourceRange depthRange_;

 public:
  SourceRange depthRange() const { return depthRange_; }
};

}  // namespace

std::unique_ptr<Module> buildAst(void* fileContext, FileId file, const TokenRangeFn& tokenRange, bool* depthExceeded,
                                 SourceRange* depthRange) {
  Builder builder(file, tokenRange);
  auto module = builder.build(static_cast<P::FileContext*>(fileContext));
  if (depthExceeded != nullptr) *depthExceeded = builder.depthExceeded();
  if (depthRange != nullptr) *depthRange = builder.depthRange();
  return module;
}

}  // namespace cbtl
