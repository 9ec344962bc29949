// AST builder: declarations. Top-level declarations, the statements of a scope (var, require, sample,
// cost), personalized generators with their clauses, skills with their action blocks, and tasks.
#include "compiler/ast/AstBuilderInternal.h"

#include <cstdint>

namespace cbtl::detail {

std::unique_ptr<Decl> AstBuilder::topDecl(P::TopDeclContext* ctx) {
  if (auto* c = ctx->domainDecl()) {  // a misplaced or repeated header; name resolution reports it (E0211)
    auto d = start<DomainDecl>(c);
    if (c->qualifiedName() != nullptr) d->name = qualified(c->qualifiedName());
    return d;
  }
  if (auto* c = ctx->importDecl()) return importDecl(c);
  if (auto* c = ctx->worldDecl()) {
    auto d = start<WorldDecl>(c);
    if (c->STRING() != nullptr) {
      d->path = unquote(c->STRING()->getText());
      d->pathRange = range(c->STRING());
    }
    return d;
  }
  if (auto* c = ctx->simulatorDecl()) {
    auto d = start<SimulatorDecl>(c);
    if (c->STRING() != nullptr) d->command = unquote(c->STRING()->getText());
    return d;
  }
  if (auto* c = ctx->robotDecl()) {
    auto d = start<RobotDecl>(c);
    d->name = ident(c->ident());
    d->fields = fieldInits(c->fieldInit());
    return d;
  }
  if (auto* c = ctx->clearanceDecl()) return clearance(c);
  if (auto d = dataDecl(ctx)) return d;
  if (auto d = callableDecl(ctx)) return d;
  if (auto* c = ctx->personalDecl()) return personal(c);
  if (auto* c = ctx->skillDecl()) return skill(c);
  if (auto* c = ctx->taskDecl()) return task(c);
  if (auto* c = ctx->scopeStmt()) return scopeStmt(c);
  return nullptr;
}

std::unique_ptr<Decl> AstBuilder::importDecl(P::ImportDeclContext* c) {
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

std::unique_ptr<Decl> AstBuilder::dataDecl(P::TopDeclContext* ctx) {
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
  return nullptr;
}

std::unique_ptr<Decl> AstBuilder::callableDecl(P::TopDeclContext* ctx) {
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
  return nullptr;
}

void AstBuilder::callable(CallableDecl& d, P::IdentContext* name, P::TypeParamsContext* tps, P::ParamListContext* ps,
                          P::TypeRefContext* result) {
  d.name = ident(name);
  if (tps != nullptr) {
    for (auto* id : tps->ident()) d.typeParams.push_back(ident(id));
  }
  d.params = params(ps);
  if (result != nullptr) d.result = std::make_unique<TypeRef>(typeRef(result));
}

std::unique_ptr<Decl> AstBuilder::scopeStmt(P::ScopeStmtContext* ctx) {
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

// A `per` key: its expression and its source text (tokens as written, whitespace collapsed to one space), which
// names the key in messages and profiles: `per kindOf[p]` is the key "kindOf[p]".
PerKey AstBuilder::perKey(P::ExprContext* ctx) {
  PerKey key;
  key.spelling.range = range(ctx);
  if (ctx->start != nullptr && ctx->stop != nullptr && ctx->stop->getStopIndex() >= ctx->start->getStartIndex()) {
    const std::string raw = ctx->start->getInputStream()->getText(
        antlr4::misc::Interval(ctx->start->getStartIndex(), ctx->stop->getStopIndex()));
    for (const char c : raw) {
      const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
      if (!space)
        key.spelling.name += c;
      else if (!key.spelling.name.empty() && key.spelling.name.back() != ' ')
        key.spelling.name += ' ';
    }
  }
  key.expr = expr(ctx);
  return key;
}

std::unique_ptr<Decl> AstBuilder::personal(P::PersonalDeclContext* ctx) {
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
      for (auto* k : m->expr()) d->perKeys.push_back(perKey(k));
    } else if (auto* a = dynamic_cast<P::AcceptClauseContext*>(clause)) {
      d->accepts.push_back(expr(a->expr()));
    } else if (auto* fb = dynamic_cast<P::FallbackClauseContext*>(clause)) {
      d->fallbacks.push_back(expr(fb->expr()));
    } else if (auto* ex = dynamic_cast<P::ExploreClauseContext*>(clause)) {
      d->explores.push_back(ident(ex->ident()));
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

std::unique_ptr<ActionStmt> AstBuilder::actionStmt(P::ActionStmtContext* ctx) {
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
  } else if (auto* al = dynamic_cast<P::ActionAllowContext*>(ctx)) {
    s->kind = ActionStmtKind::Allow;
    s->allow = allowClause(al);
    for (auto* b : al->actionStmt()) s->body.push_back(actionStmt(b));
  }
  return s;
}

std::unique_ptr<Decl> AstBuilder::skill(P::SkillDeclContext* ctx) {
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

SkillInstance AstBuilder::skillInstance(P::SkillInstanceContext* ctx) {
  SkillInstance inst;
  inst.range = range(ctx);
  const auto ids = ctx->ident();
  if (!ids.empty()) inst.skill = ident(ids[0]);
  if (ctx->AS() != nullptr && ids.size() >= 2) inst.alias = ident(ids[1]);
  inst.hasArgs = ctx->LPAREN() != nullptr;
  if (ctx->argList() != nullptr) inst.args = args(ctx->argList());
  return inst;
}

std::unique_ptr<Decl> AstBuilder::task(P::TaskDeclContext* ctx) {
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

}  // namespace cbtl::detail
