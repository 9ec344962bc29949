// lower: compile-time values. Family indices, the members of a family's index set or a `for` set, the
// bindings of an unrolled `forall` and its `where` condition are evaluated here; anything else stays an
// expression of the graph that the runtime evaluates.
#include "compiler/lower/LoweringInternal.h"

#include <cmath>

namespace cbtl::detail {

CVal enumMemberValue(const EnumDecl& en, int index) {
  CVal v;
  v.kind = CVal::Kind::Enum;
  v.decl = &en;
  v.index = index;
  v.text = en.members[index].name;
  return v;
}

CVal itemEntryValue(const ItemsDecl& items, int index) {
  CVal v;
  v.kind = CVal::Kind::Item;
  v.decl = &items;
  v.index = index;
  v.text = items.entries[index].name.name;
  return v;
}

std::optional<CVal> Lowerer::evalConst(const Expr* e, const Ctx& ctx) {
  if (e == nullptr) return std::nullopt;
  switch (e->kind) {
    case ExprKind::String: {
      CVal v;
      v.kind = CVal::Kind::Text;
      v.text = e->text;
      return v;
    }
    case ExprKind::Number:
      if (e->number == std::floor(e->number) && std::fabs(e->number) < 1e15) {
        CVal v;
        v.kind = CVal::Kind::Int;
        v.number = static_cast<long long>(e->number);
        v.text = std::to_string(v.number);
        return v;
      }
      return std::nullopt;
    case ExprKind::Unary:
      if (e->unaryOp == UnaryOp::Neg) {
        auto v = evalConst(e->operands[0].get(), ctx);
        if (v && v->kind == CVal::Kind::Int) {
          v->number = -v->number;
          v->text = std::to_string(v->number);
          return v;
        }
      }
      return std::nullopt;
    case ExprKind::Binary:
      return evalConstArithmetic(*e, ctx);
    case ExprKind::Name:
    case ExprKind::Member:
      return evalConstName(*e, ctx);
    default:
      return std::nullopt;
  }
}

std::optional<CVal> Lowerer::evalConstArithmetic(const Expr& e, const Ctx& ctx) {
  if (e.binaryOp != BinaryOp::Add && e.binaryOp != BinaryOp::Sub && e.binaryOp != BinaryOp::Mul) return std::nullopt;
  auto a = evalConst(e.operands[0].get(), ctx), b = evalConst(e.operands[1].get(), ctx);
  if (!a || !b || a->kind != CVal::Kind::Int || b->kind != CVal::Kind::Int) return std::nullopt;
  CVal v;
  v.kind = CVal::Kind::Int;
  // A result that does not fit in 64 bits is not a usable index or bound: not a compile-time value.
  const bool overflow = e.binaryOp == BinaryOp::Add   ? __builtin_add_overflow(a->number, b->number, &v.number)
                        : e.binaryOp == BinaryOp::Sub ? __builtin_sub_overflow(a->number, b->number, &v.number)
                                                      : __builtin_mul_overflow(a->number, b->number, &v.number);
  if (overflow) return std::nullopt;
  v.text = std::to_string(v.number);
  return v;
}

std::optional<CVal> Lowerer::evalConstName(const Expr& e, const Ctx& ctx) {
  if (e.ref.kind == RefKind::EnumMember) {
    return enumMemberValue(static_cast<const EnumDecl&>(*e.ref.decl), e.ref.index);
  }
  if (e.ref.kind == RefKind::ItemEntry) {
    return itemEntryValue(static_cast<const ItemsDecl&>(*e.ref.decl), e.ref.index);
  }
  if (e.ref.kind == RefKind::Binder) {
    auto it = ctx.env.find(e.ref.binder);
    if (it != ctx.env.end()) return it->second;
  }
  if (e.ref.kind == RefKind::Const) {
    const auto* c = static_cast<const ConstDecl*>(e.ref.decl);
    if (!c->index) return evalConst(c->value.get(), ctx);
  }
  return std::nullopt;
}

std::optional<std::vector<CVal>> Lowerer::enumerate(const Expr* set, const Ctx& ctx, bool* tooLarge) {
  if (set == nullptr) return std::nullopt;
  if ((set->kind == ExprKind::Name) && set->ref.kind == RefKind::EnumType) {
    const auto& en = static_cast<const EnumDecl&>(*set->ref.decl);
    std::vector<CVal> out;
    for (std::size_t i = 0; i < en.members.size(); ++i) out.push_back(enumMemberValue(en, static_cast<int>(i)));
    return out;
  }
  if (set->kind == ExprKind::Name && set->ref.kind == RefKind::ItemSet) {
    const auto& items = static_cast<const ItemsDecl&>(*set->ref.decl);
    std::vector<CVal> out;
    for (std::size_t i = 0; i < items.entries.size(); ++i) out.push_back(itemEntryValue(items, static_cast<int>(i)));
    return out;
  }
  if (set->kind == ExprKind::Range) return enumerateRange(*set, ctx, tooLarge);
  if (set->kind == ExprKind::Name && set->ref.kind == RefKind::Const) {  // a constant list, e.g. knownMeals
    const auto* c = static_cast<const ConstDecl*>(set->ref.decl);
    if (!c->index) return enumerate(c->value.get(), ctx, tooLarge);
  }
  if (set->kind == ExprKind::List) {
    std::vector<CVal> out;
    for (const auto& op : set->operands) {
      auto v = evalConst(op.get(), ctx);
      if (!v) return std::nullopt;
      out.push_back(*v);
    }
    return out;
  }
  return std::nullopt;
}

std::optional<std::vector<CVal>> Lowerer::enumerateRange(const Expr& range, const Ctx& ctx, bool* tooLarge) {
  auto lo = evalConst(range.operands[0].get(), ctx), hi = evalConst(range.operands[1].get(), ctx);
  if (!lo || !hi || lo->kind != CVal::Kind::Int || hi->kind != CVal::Kind::Int) return std::nullopt;
  long long span = 0;
  if (__builtin_sub_overflow(hi->number, lo->number, &span) || span >= static_cast<long long>(kMaxSetSize)) {
    if (tooLarge != nullptr) *tooLarge = true;
    return std::nullopt;
  }
  std::vector<CVal> out;
  for (long long i = lo->number; i <= hi->number; ++i) {
    CVal v;
    v.kind = CVal::Kind::Int;
    v.number = i;
    v.text = std::to_string(i);
    out.push_back(v);
  }
  return out;
}

std::optional<bool> Lowerer::decide(const Expr* e, const Ctx& ctx) {
  if (e == nullptr) return true;
  if (e->kind == ExprKind::Bool) return e->boolean;
  if (e->kind == ExprKind::Unary && e->unaryOp == UnaryOp::Not) {
    auto v = decide(e->operands[0].get(), ctx);
    return v ? std::optional<bool>(!*v) : std::nullopt;
  }
  if (e->kind != ExprKind::Binary) return std::nullopt;
  if (e->binaryOp == BinaryOp::And || e->binaryOp == BinaryOp::Or) {
    auto a = decide(e->operands[0].get(), ctx), b = decide(e->operands[1].get(), ctx);
    if (!a || !b) return std::nullopt;
    return e->binaryOp == BinaryOp::And ? (*a && *b) : (*a || *b);
  }
  return decideComparison(*e, ctx);
}

std::optional<bool> Lowerer::decideComparison(const Expr& e, const Ctx& ctx) {
  auto a = evalConst(e.operands[0].get(), ctx), b = evalConst(e.operands[1].get(), ctx);
  if (!a || !b || a->kind != b->kind) return std::nullopt;
  if (a->kind != CVal::Kind::Int) {
    // Members and entries are equal when they are the same member of the same declaration (two item sets
    // may hold entries of one type at the same position); strings by their text. Only enum members of
    // one enum are ordered (by declaration order).
    const bool same = a->kind == CVal::Kind::Text ? a->text == b->text : a->decl == b->decl && a->index == b->index;
    if (e.binaryOp == BinaryOp::Eq) return same;
    if (e.binaryOp == BinaryOp::Ne) return !same;
    if (a->kind != CVal::Kind::Enum || a->decl != b->decl) return std::nullopt;
  }
  const long long x = a->kind == CVal::Kind::Int ? a->number : a->index;
  const long long y = b->kind == CVal::Kind::Int ? b->number : b->index;
  switch (e.binaryOp) {
    case BinaryOp::Eq:
      return x == y;
    case BinaryOp::Ne:
      return x != y;
    case BinaryOp::Lt:
      return x < y;
    case BinaryOp::Le:
      return x <= y;
    case BinaryOp::Gt:
      return x > y;
    case BinaryOp::Ge:
      return x >= y;
    default:
      return std::nullopt;
  }
}

ir::Expr Lowerer::constNode(const CVal& v, const Type* t) {
  ir::Expr x;
  x.type = typeDesc(t);
  if (v.kind == CVal::Kind::Int) {
    x.op = ir::Op::Num;
    x.number = static_cast<double>(v.number);
    x.text = v.text;
  } else if (v.kind == CVal::Kind::Enum) {
    x.op = ir::Op::Enum;
    x.extra = v.decl->name.name;
    x.text = v.text;
  } else if (v.kind == CVal::Kind::Text) {
    x.op = ir::Op::Str;
    x.text = v.text;
  } else {
    x.op = ir::Op::Item;
    x.extra = v.decl->name.name;
    x.text = v.text;
  }
  return x;
}

}  // namespace cbtl::detail
