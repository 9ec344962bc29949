// lower: expressions. The graph's expressions mirror the AST's; names become variable, parameter,
// constant, observation or literal nodes, and a family indexed at compile time becomes its member.
#include "compiler/lower/LoweringInternal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cbtl::detail {

ir::TypeDesc typeDesc(const Type* t) {
  if (t == nullptr) return {ir::TypeKind::Void, "void"};
  // In TypeKind's order.
  static const ir::TypeKind kinds[] = {ir::TypeKind::Error, ir::TypeKind::Real,  ir::TypeKind::Int,  ir::TypeKind::Bool,
                                       ir::TypeKind::Text,  ir::TypeKind::Enum,  ir::TypeKind::Item, ir::TypeKind::Vec,
                                       ir::TypeKind::SE2,   ir::TypeKind::SE3,   ir::TypeKind::Conf, ir::TypeKind::Set,
                                       ir::TypeKind::Tuple, ir::TypeKind::Range, ir::TypeKind::Void};
  return {kinds[static_cast<int>(t->kind)], t->spelling};
}

namespace {

ir::Op irOp(BinaryOp op) {
  switch (op) {
    case BinaryOp::Add:
      return ir::Op::Add;
    case BinaryOp::Sub:
      return ir::Op::Sub;
    case BinaryOp::Mul:
      return ir::Op::Mul;
    case BinaryOp::Div:
      return ir::Op::Div;
    case BinaryOp::Mod:
      return ir::Op::Mod;
    case BinaryOp::Pow:
      return ir::Op::Pow;
    case BinaryOp::Eq:
      return ir::Op::Eq;
    case BinaryOp::Ne:
      return ir::Op::Ne;
    case BinaryOp::Lt:
      return ir::Op::Lt;
    case BinaryOp::Le:
      return ir::Op::Le;
    case BinaryOp::Gt:
      return ir::Op::Gt;
    case BinaryOp::Ge:
      return ir::Op::Ge;
    case BinaryOp::And:
      return ir::Op::And;
    case BinaryOp::Or:
      return ir::Op::Or;
    case BinaryOp::Implies:
      return ir::Op::Implies;
    case BinaryOp::Iff:
      return ir::Op::Iff;
  }
  return ir::Op::Invalid;
}

}  // namespace

ir::Expr Lowerer::lower(const Expr* e, Ctx& ctx) {
  ir::Expr x;
  if (e == nullptr) {
    x.op = ir::Op::Bool;
    x.number = 1;
    x.type = {ir::TypeKind::Bool, "bool"};
    return x;
  }
  x.type = typeDesc(e->type);
  switch (e->kind) {
    case ExprKind::Number:
      x.op = ir::Op::Num;
      x.number = e->number;
      x.text = e->text;
      return x;
    case ExprKind::String:
      x.op = ir::Op::Str;
      x.text = e->text;
      return x;
    case ExprKind::Bool:
      x.op = ir::Op::Bool;
      x.number = e->boolean ? 1 : 0;
      return x;
    case ExprKind::Name:
    case ExprKind::Member:
      if (e->kind == ExprKind::Member && e->ref.kind != RefKind::EnumMember && e->ref.kind != RefKind::ItemEntry) {
        x.op = ir::Op::Member;
        x.text = e->text;
        x.children.push_back(lower(e->operands[0].get(), ctx));
        return x;
      }
      return lowerName(*e, ctx, x);
    case ExprKind::Call: {
      x.op = ir::Op::Call;
      x.text = e->operands[0]->text;
      const auto* callee = static_cast<const CallableDecl*>(e->ref.decl);
      for (const auto* a : orderedArgs(callee, e->args)) x.children.push_back(lower(a->value.get(), ctx));
      return x;
    }
    case ExprKind::Index: {
      const Expr* base = e->operands[0].get();
      if (base->kind == ExprKind::Name && (base->ref.kind == RefKind::Variable || base->ref.kind == RefKind::Const ||
                                           base->ref.kind == RefKind::Observation)) {
        return lowerFamilyIndex(*e, ctx, x);
      }
      x.op = ir::Op::Index;
      for (const auto& op : e->operands) x.children.push_back(lower(op.get(), ctx));
      return x;
    }
    case ExprKind::Unary:
      x.op = e->unaryOp == UnaryOp::Neg ? ir::Op::Neg : ir::Op::Not;
      x.children.push_back(lower(e->operands[0].get(), ctx));
      return x;
    case ExprKind::Binary:
      x.op = irOp(e->binaryOp);
      x.children.push_back(lower(e->operands[0].get(), ctx));
      x.children.push_back(lower(e->operands[1].get(), ctx));
      return x;
    case ExprKind::Range:
    case ExprKind::In:
      x.op = e->kind == ExprKind::Range ? ir::Op::Range : ir::Op::In;
      x.children.push_back(lower(e->operands[0].get(), ctx));
      x.children.push_back(lower(e->operands[1].get(), ctx));
      return x;
    case ExprKind::Quantifier: {
      checkQuantifierNest(*e, ctx);
      ++quantifierNesting_;
      x.op = e->quant == QuantKind::Forall ? ir::Op::Forall : ir::Op::Exists;
      for (const auto& n : e->binder->names) x.names.push_back(n->name.name);
      x.children.push_back(lower(e->binder->set.get(), ctx));
      x.children.push_back(lower(e->operands[0].get(), ctx));
      x.children.push_back(lower(e->operands[1].get(), ctx));
      --quantifierNesting_;
      return x;
    }
    case ExprKind::If:
      x.op = ir::Op::If;
      for (const auto& op : e->operands) x.children.push_back(lower(op.get(), ctx));
      return x;
    case ExprKind::Tuple:
    case ExprKind::List:
      x.op = e->kind == ExprKind::Tuple ? ir::Op::Tuple : ir::Op::List;
      for (const auto& op : e->operands) x.children.push_back(lower(op.get(), ctx));
      return x;
  }
  return x;
}

std::vector<const Arg*> Lowerer::orderedArgs(const CallableDecl* callee, const std::vector<Arg>& args) {
  std::vector<const Arg*> out;
  if (callee == nullptr) {
    for (const auto& a : args) out.push_back(&a);
    return out;
  }
  out.assign(callee->params.size(), nullptr);
  std::size_t next = 0;
  for (const auto& a : args) {
    if (a.name.name.empty()) {
      if (next < out.size()) out[next++] = &a;
      continue;
    }
    for (std::size_t i = 0; i < callee->params.size(); ++i) {
      if (callee->params[i].name.name == a.name.name) out[i] = &a;
    }
  }
  out.erase(std::remove(out.begin(), out.end(), nullptr), out.end());
  return out;
}

ir::Expr& Lowerer::lowerName(const Expr& e, Ctx& ctx, ir::Expr& x) {
  const NameRef& r = e.ref;
  switch (r.kind) {
    case RefKind::Variable: {
      x.op = ir::Op::Var;
      x.text = e.text;
      x.id = varId(r.decl, "", ctx);
      return x;
    }
    case RefKind::Param: {
      // Inside a skill instance a parameter is the argument the task passed (lowerSkillInstance).
      if (r.decl->kind == DeclKind::Skill && ctx.skill == r.decl &&
          r.index < static_cast<int>(ctx.skillParams.size()) && ctx.skillParams[r.index]) {
        x = *ctx.skillParams[r.index];
        return x;
      }
      x.op = ir::Op::Param;
      x.id = r.index;
      x.text = e.text;
      return x;
    }
    case RefKind::Const: {
      const auto* c = static_cast<const ConstDecl*>(r.decl);
      x.op = ir::Op::Const;
      x.text = c->name.name;
      return x;
    }
    case RefKind::EnumMember:
      x = constNode(enumMemberValue(static_cast<const EnumDecl&>(*r.decl), r.index), e.type);
      return x;
    case RefKind::ItemEntry:
      x = constNode(itemEntryValue(static_cast<const ItemsDecl&>(*r.decl), r.index), e.type);
      return x;
    case RefKind::EnumType:
      x.op = ir::Op::EnumSet;
      x.text = r.decl->name.name;
      return x;
    case RefKind::ItemSet:
      x.op = ir::Op::ItemSet;
      x.text = r.decl->name.name;
      return x;
    case RefKind::Observation:
      x.op = ir::Op::Obs;
      x.text = r.decl->name.name;
      return x;
    case RefKind::Binder: {
      auto it = ctx.env.find(r.binder);
      if (it != ctx.env.end()) {
        x = constNode(it->second, e.type);
        return x;
      }
      x.op = ir::Op::Local;
      x.text = e.text;
      return x;
    }
    case RefKind::Builtin:
      x.op = ir::Op::Num;
      x.number = M_PI;
      x.text = "pi";
      return x;
    default:
      x.op = ir::Op::Invalid;
      x.text = e.text;
      return x;
  }
}

ir::Expr& Lowerer::lowerFamilyIndex(const Expr& e, Ctx& ctx, ir::Expr& x) {
  const Expr* base = e.operands[0].get();
  const Expr* index = e.operands.size() > 1 ? e.operands[1].get() : nullptr;
  auto v = evalConst(index, ctx);
  const Decl* decl = base->ref.decl;
  if (base->ref.kind == RefKind::Variable) {
    auto& members = ctx.vars[decl];
    if (members.empty()) members = lookupVars(decl, ctx);
    if (v) {
      auto it = members.find(v->text);
      if (it != members.end()) {
        x.op = ir::Op::Var;
        x.text = fmt::format("{}[{}]", base->text, v->text);
        x.id = it->second;
        return x;
      }
    }
    x.op = ir::Op::Family;
    x.text = base->text;
    for (const auto& [k, id] : members) x.vars.push_back(id);
    x.children.push_back(lower(index, ctx));
    return x;
  }
  x.op = base->ref.kind == RefKind::Const ? ir::Op::Const : ir::Op::Obs;
  x.text = base->text;
  x.children.push_back(lower(index, ctx));
  return x;
}

std::map<std::string, ir::VarId> Lowerer::lookupVars(const Decl* decl, const Ctx& ctx) {
  if (auto it = ctx.vars.find(decl); it != ctx.vars.end() && !it->second.empty()) return it->second;
  if (auto it = globalCtx_.vars.find(decl); it != globalCtx_.vars.end()) return it->second;
  return {};
}

ir::VarId Lowerer::varId(const Decl* decl, const std::string& member, Ctx& ctx) {
  auto members = lookupVars(decl, ctx);
  auto it = members.find(member);
  return it == members.end() ? 0xffffffffu : it->second;
}

void Lowerer::collectVars(const ir::Expr& x, std::set<ir::VarId>& out) {
  if (x.op == ir::Op::Var && x.id >= 0) out.insert(static_cast<ir::VarId>(x.id));
  for (ir::VarId v : x.vars) out.insert(v);
  for (const auto& c : x.children) collectVars(c, out);
}

}  // namespace cbtl::detail
