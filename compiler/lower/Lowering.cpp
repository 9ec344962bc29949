#include "compiler/lower/Lowering.h"

#include "compiler/lower/UsageWarnings.h"
#include "compiler/sema/GeneratorChecker.h"
#include "compiler/sema/Type.h"
#include "compiler/sema/TypeChecker.h"
#include "ir/OpNames.h"
#include "ir/Pattern.h"
#include "ir/ReadSet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace cbtl {
namespace {

// A value known at compile time, used for family indices and quantifier bindings.
struct CVal {
  enum class Kind { Enum, Int, Item, Text, None } kind = Kind::None;
  std::string text;  // member / entry name, the integer as text, or the string
  long long number = 0;
  const Decl* decl = nullptr;  // EnumDecl or ItemsDecl
  int index = -1;
};

ir::TypeDesc typeDesc(const Type* t) {
  if (t == nullptr) return {ir::TypeKind::Void, "void"};
  // In TypeKind's order.
  static const ir::TypeKind kinds[] = {ir::TypeKind::Error, ir::TypeKind::Real,  ir::TypeKind::Int,  ir::TypeKind::Bool,
                                       ir::TypeKind::Text,  ir::TypeKind::Enum,  ir::TypeKind::Item, ir::TypeKind::Vec,
                                       ir::TypeKind::SE2,   ir::TypeKind::SE3,   ir::TypeKind::Conf, ir::TypeKind::Set,
                                       ir::TypeKind::Tuple, ir::TypeKind::Range, ir::TypeKind::Void};
  return {kinds[static_cast<int>(t->kind)], t->spelling};
}

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

class Lowerer {
 public:
  Lowerer(const GlobalSymbols& symbols, const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& g)
      : symbols_(symbols), sources_(sources), diags_(diags), g_(g) {}

  void run(const std::vector<std::unique_ptr<Module>>& modules) {
    g_.domain = symbols_.domainName;
    if (symbols_.world) g_.world = symbols_.world->path;
    for (const auto& m : modules) {
      for (const auto& d : m->decls) declareTop(*d);
    }
    // Global scope: shared by every task.
    Ctx global;
    global.scope = "global";
    lowerBody(symbols_.globalScope, global, globalVars_, globalConstraints_, globalSamplers_, globalCosts_);
    globalCtx_ = global;
    lowerFunctionBodies();

    bool anyTask = false;
    std::set<std::string> usedSkills;
    for (const auto& m : modules) {
      for (const auto& d : m->decls) {
        if (d->kind != DeclKind::Task) continue;
        anyTask = true;
        lowerTask(static_cast<const TaskDecl&>(*d), usedSkills);
      }
    }
    if (!anyTask) {
      ir::Task t;
      t.name = "main";
      t.implicit = true;
      t.vars = globalVars_;
      t.constraints = globalConstraints_;
      t.samplers = globalSamplers_;
      t.costs = globalCosts_;
      g_.tasks.push_back(std::move(t));
    }
    for (const auto& [name, skill] : symbols_.skills) {
      if (!usedSkills.count(name) && anyTask) {
        diags_.warning("W0501", skill->name.range, fmt::format("skill '{}' is not run by any task", name));
      }
    }
    for (const auto& m : modules) {
      for (const auto& d : m->decls) {
        if (d->kind == DeclKind::Personal) lowerGenerator(static_cast<const PersonalDecl&>(*d));
      }
    }
    followCallsInReadSets();
    if (!tooLarge_) reportUsageWarnings(g_, declOf_, diags_);
  }

 private:
  struct Ctx {
    std::string scope;
    std::string prefix;                                            // "<instance>." for skill instances
    std::map<const Decl*, std::map<std::string, ir::VarId>> vars;  // VarDecl -> member text ("" if scalar) -> id
    const SkillDecl* skill = nullptr;
    std::vector<std::optional<ir::Expr>> skillParams;  // lowered expression per skill parameter (a var node)
    std::map<const BinderDecl*, CVal> env;
  };

  ir::Span span(SourceRange r) const {
    ir::Span s;
    if (!r.valid()) return s;
    s.file = sources_.file(r.file).path;
    LineCol a = sources_.position(r.file, r.begin), b = sources_.position(r.file, r.end);
    s.line = a.line;
    s.column = a.column;
    s.endLine = b.line;
    s.endColumn = b.column;
    return s;
  }

  // --- compile-time values ------------------------------------------------------------------

  std::optional<CVal> evalConst(const Expr* e, const Ctx& ctx) {
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
      case ExprKind::Binary: {
        if (e->binaryOp != BinaryOp::Add && e->binaryOp != BinaryOp::Sub && e->binaryOp != BinaryOp::Mul)
          return std::nullopt;
        auto a = evalConst(e->operands[0].get(), ctx), b = evalConst(e->operands[1].get(), ctx);
        if (!a || !b || a->kind != CVal::Kind::Int || b->kind != CVal::Kind::Int) return std::nullopt;
        CVal v;
        v.kind = CVal::Kind::Int;
        // A result that does not fit in 64 bits is not a usable index or bound: not a compile-time value.
        const bool overflow = e->binaryOp == BinaryOp::Add   ? __builtin_add_overflow(a->number, b->number, &v.number)
                              : e->binaryOp == BinaryOp::Sub ? __builtin_sub_overflow(a->number, b->number, &v.number)
                                                             : __builtin_mul_overflow(a->number, b->number, &v.number);
        if (overflow) return std::nullopt;
        v.text = std::to_string(v.number);
        return v;
      }
      case ExprKind::Name:
      case ExprKind::Member:
        if (e->ref.kind == RefKind::EnumMember) {
          const auto* en = static_cast<const EnumDecl*>(e->ref.decl);
          CVal v;
          v.kind = CVal::Kind::Enum;
          v.decl = en;
          v.index = e->ref.index;
          v.text = en->members[e->ref.index].name;
          return v;
        }
        if (e->ref.kind == RefKind::ItemEntry) {
          const auto* items = static_cast<const ItemsDecl*>(e->ref.decl);
          CVal v;
          v.kind = CVal::Kind::Item;
          v.decl = items;
          v.index = e->ref.index;
          v.text = items->entries[e->ref.index].name.name;
          return v;
        }
        if (e->ref.kind == RefKind::Binder) {
          auto it = ctx.env.find(e->ref.binder);
          if (it != ctx.env.end()) return it->second;
        }
        if (e->ref.kind == RefKind::Const) {
          const auto* c = static_cast<const ConstDecl*>(e->ref.decl);
          if (!c->index) return evalConst(c->value.get(), ctx);
        }
        return std::nullopt;
      default:
        return std::nullopt;
    }
  }

  // The members of a compile-time finite set, or nullopt if it is not known at compile time or (then
  // *tooLarge is set) is an integer range of more than kMaxSetSize members.
  std::optional<std::vector<CVal>> enumerate(const Expr* set, const Ctx& ctx, bool* tooLarge = nullptr) {
    if (set == nullptr) return std::nullopt;
    if ((set->kind == ExprKind::Name) && set->ref.kind == RefKind::EnumType) {
      const auto* en = static_cast<const EnumDecl*>(set->ref.decl);
      std::vector<CVal> out;
      for (std::size_t i = 0; i < en->members.size(); ++i) {
        CVal v;
        v.kind = CVal::Kind::Enum;
        v.decl = en;
        v.index = static_cast<int>(i);
        v.text = en->members[i].name;
        out.push_back(v);
      }
      return out;
    }
    if (set->kind == ExprKind::Name && set->ref.kind == RefKind::ItemSet) {
      const auto* items = static_cast<const ItemsDecl*>(set->ref.decl);
      std::vector<CVal> out;
      for (std::size_t i = 0; i < items->entries.size(); ++i) {
        CVal v;
        v.kind = CVal::Kind::Item;
        v.decl = items;
        v.index = static_cast<int>(i);
        v.text = items->entries[i].name.name;
        out.push_back(v);
      }
      return out;
    }
    if (set->kind == ExprKind::Range) {
      auto lo = evalConst(set->operands[0].get(), ctx), hi = evalConst(set->operands[1].get(), ctx);
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

  // Decides a `where` condition at compile time when it only compares bound values.
  std::optional<bool> decide(const Expr* e, const Ctx& ctx) {
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
    auto a = evalConst(e->operands[0].get(), ctx), b = evalConst(e->operands[1].get(), ctx);
    if (!a || !b || a->kind != b->kind) return std::nullopt;
    if (a->kind != CVal::Kind::Int) {
      // Members and entries are equal when they are the same member of the same declaration (two item sets
      // may hold entries of one type at the same position); strings by their text. Only enum members of
      // one enum are ordered (by declaration order).
      const bool same = a->kind == CVal::Kind::Text ? a->text == b->text : a->decl == b->decl && a->index == b->index;
      if (e->binaryOp == BinaryOp::Eq) return same;
      if (e->binaryOp == BinaryOp::Ne) return !same;
      if (a->kind != CVal::Kind::Enum || a->decl != b->decl) return std::nullopt;
    }
    const long long x = a->kind == CVal::Kind::Int ? a->number : a->index;
    const long long y = b->kind == CVal::Kind::Int ? b->number : b->index;
    switch (e->binaryOp) {
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

  ir::Expr constNode(const CVal& v, const Type* t) {
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

  // --- expressions --------------------------------------------------------------------------

  ir::Expr lower(const Expr* e, Ctx& ctx) {
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
        x.op = e->quant == QuantKind::Forall ? ir::Op::Forall : ir::Op::Exists;
        for (const auto& n : e->binder->names) x.names.push_back(n->name.name);
        x.children.push_back(lower(e->binder->set.get(), ctx));
        x.children.push_back(lower(e->operands[0].get(), ctx));
        x.children.push_back(lower(e->operands[1].get(), ctx));
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

  std::vector<const Arg*> orderedArgs(const CallableDecl* callee, const std::vector<Arg>& args) {
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

  ir::Expr& lowerName(const Expr& e, Ctx& ctx, ir::Expr& x) {
    const NameRef& r = e.ref;
    switch (r.kind) {
      case RefKind::Variable: {
        x.op = ir::Op::Var;
        x.text = e.text;
        x.id = varId(r.decl, "", ctx);
        return x;
      }
      case RefKind::Param: {
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
      case RefKind::EnumMember: {
        CVal v;
        v.kind = CVal::Kind::Enum;
        v.decl = r.decl;
        v.index = r.index;
        v.text = static_cast<const EnumDecl*>(r.decl)->members[r.index].name;
        x = constNode(v, e.type);
        return x;
      }
      case RefKind::ItemEntry: {
        CVal v;
        v.kind = CVal::Kind::Item;
        v.decl = r.decl;
        v.index = r.index;
        v.text = static_cast<const ItemsDecl*>(r.decl)->entries[r.index].name.name;
        x = constNode(v, e.type);
        return x;
      }
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

  ir::Expr& lowerFamilyIndex(const Expr& e, Ctx& ctx, ir::Expr& x) {
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

  // Variables visible in a context: its own, then the global ones.
  std::map<std::string, ir::VarId> lookupVars(const Decl* decl, const Ctx& ctx) {
    if (auto it = ctx.vars.find(decl); it != ctx.vars.end() && !it->second.empty()) return it->second;
    if (auto it = globalCtx_.vars.find(decl); it != globalCtx_.vars.end()) return it->second;
    return {};
  }

  ir::VarId varId(const Decl* decl, const std::string& member, Ctx& ctx) {
    auto members = lookupVars(decl, ctx);
    auto it = members.find(member);
    return it == members.end() ? 0xffffffffu : it->second;
  }

  void lowerFunctionBodies() {
    for (const auto& [index, decl] : pendingBodies_) {
      Ctx none;
      g_.functions[index].body = lower(decl->body.get(), none);
    }
    pendingBodies_.clear();
  }

  // Read sets as the runtime evaluates them: with every called function's body inlined (ir/ReadSet.h).
  // Done once everything is lowered, so a function declared after its caller is followed too.
  void followCallsInReadSets() {
    auto readSet = [this](const ir::Expr& e, std::vector<ir::VarId>& vars) {
      std::set<ir::VarId> all(vars.begin(), vars.end());
      ir::collectReadVars(g_, e, all);
      vars.assign(all.begin(), all.end());
    };
    for (auto& c : g_.constraints) readSet(c.expr, c.vars);
    for (auto& c : g_.costs) readSet(c.expr, c.vars);
    for (auto& smp : g_.samplers) {
      for (const auto& a : smp.args) readSet(a, smp.reads);
    }
  }

  static void collectVars(const ir::Expr& x, std::set<ir::VarId>& out) {
    if (x.op == ir::Op::Var && x.id >= 0) out.insert(static_cast<ir::VarId>(x.id));
    for (ir::VarId v : x.vars) out.insert(v);
    for (const auto& c : x.children) collectVars(c, out);
  }

  // --- size limits --------------------------------------------------------------------------

  // Families, unrolled foralls, sample `for` sets and skill instances multiply declarations. These limits
  // turn a blow-up (a typo such as 0 .. 1000000, or a fuzzer's input) into a diagnostic instead of an
  // exhausted machine. kMaxSetSize bounds one integer range used as a family index or `for` set;
  // kMaxGraphSize bounds the whole graph in units of one variable, constraint, sampler, cost or action plus
  // one per expression node. Real programs stay orders of magnitude below both.
  static constexpr std::size_t kMaxSetSize = 100000;
  static constexpr std::size_t kMaxGraphSize = 2000000;
  // A top-level forall is unrolled only while the number of instances stays below this; beyond it the
  // constraint keeps its quantifier (same meaning, one hyperedge).
  static constexpr std::size_t kMaxUnrolled = 10000;

  static std::size_t nodeCount(const ir::Expr& x) {
    std::size_t n = 1;
    for (const auto& c : x.children) n += nodeCount(c);
    return n;
  }

  static std::size_t actionSize(const ir::Action& a) {
    std::size_t n = 1 + (a.set ? nodeCount(*a.set) : 0) + (a.condition ? nodeCount(*a.condition) : 0);
    for (const auto& x : a.args) n += nodeCount(x);
    for (const auto& b : a.body) n += actionSize(b);
    for (const auto& b : a.elseBody) n += actionSize(b);
    return n;
  }

  // Adds `units` to the graph's size; false (with E0317 reported once) when the graph is too large.
  bool grow(std::size_t units, SourceRange at) {
    if (tooLarge_) return false;
    graphSize_ += units;
    if (graphSize_ <= kMaxGraphSize) return true;
    tooLarge_ = true;
    diags_
        .error("E0317", at,
               fmt::format("the constraint graph is too large (more than {} variables, constraints, "
                           "samplers and expression nodes)",
                           kMaxGraphSize))
        .help("check the sizes of families, 'for' sets and unrolled 'forall's that this declaration expands");
    return false;
  }

  void tooManyMembers(SourceRange at, const char* what) {
    diags_.error("E0317", at, fmt::format("{} may have at most {} members", what, kMaxSetSize));
  }

  // --- declarations -------------------------------------------------------------------------

  void declareTop(const Decl& d) {
    switch (d.kind) {
      case DeclKind::Robot:
        g_.robots.push_back({d.name.name, static_cast<const RobotDecl&>(d).dof});
        break;
      case DeclKind::Enum: {
        ir::Enum e{d.name.name, {}, span(d.range)};
        for (const auto& m : static_cast<const EnumDecl&>(d).members) e.members.push_back(m.name);
        g_.enums.push_back(std::move(e));
        break;
      }
      case DeclKind::ItemType: {
        ir::ItemType t{d.name.name, {}, span(d.range)};
        for (const auto& f : static_cast<const ItemTypeDecl&>(d).fields)
          t.fields.push_back({f.name.name, typeDesc(f.type.resolved)});
        g_.itemTypes.push_back(std::move(t));
        break;
      }
      case DeclKind::ItemSet: {
        const auto& items = static_cast<const ItemsDecl&>(d);
        ir::ItemSet s{d.name.name, items.itemType.name.name, {}, span(d.range)};
        Ctx none;
        for (const auto& entry : items.entries) {
          ir::ItemEntry e{entry.name.name, {}};
          for (const auto& f : entry.fields) e.fields.emplace_back(f.name.name, lower(f.value.get(), none));
          s.entries.push_back(std::move(e));
        }
        g_.itemSets.push_back(std::move(s));
        break;
      }
      case DeclKind::Const: {
        const auto& c = static_cast<const ConstDecl&>(d);
        Ctx none;
        ir::Constant k{c.name.name, typeDesc(c.valueType), c.index ? c.index->elementType->spelling : "",
                       lower(c.value.get(), none), span(d.range)};
        g_.constants.push_back(std::move(k));
        break;
      }
      case DeclKind::Observe: {
        const auto& o = static_cast<const ObserveDecl&>(d);
        Ctx none;
        ir::Observation obs{o.name.name, typeDesc(o.type.resolved), std::nullopt, span(d.range)};
        if (o.index) obs.indexSet = lower(o.index->set.get(), none);
        g_.observations.push_back(std::move(obs));
        break;
      }
      case DeclKind::Feedback: {
        ir::Function f;
        f.name = d.name.name;
        f.kind = ir::FunctionKind::Feedback;
        for (const auto& p : static_cast<const FeedbackDecl&>(d).params)
          f.params.push_back({p.name.name, typeDesc(p.type.resolved)});
        f.span = span(d.range);
        g_.feedback.push_back(std::move(f));
        break;
      }
      case DeclKind::Function:
      case DeclKind::Sampler:
      case DeclKind::Action: {
        const auto& c = static_cast<const CallableDecl&>(d);
        ir::Function f;
        f.name = c.name.name;
        f.kind = d.kind == DeclKind::Function  ? ir::FunctionKind::Function
                 : d.kind == DeclKind::Sampler ? ir::FunctionKind::Sampler
                                               : ir::FunctionKind::Action;
        f.isExtern = c.isExtern;
        for (const auto& tp : c.typeParams) f.typeParams.push_back(tp.name);
        for (const auto& p : c.params) f.params.push_back({p.name.name, typeDesc(p.type.resolved)});
        f.result = c.result ? typeDesc(c.result->resolved) : ir::TypeDesc{ir::TypeKind::Void, "void"};
        // The body is lowered once the global variables exist (lowerFunctionBodies): it may read them.
        if (c.body) pendingBodies_.emplace_back(g_.functions.size(), &c);
        f.span = span(d.range);
        g_.functions.push_back(std::move(f));
        break;
      }
      case DeclKind::Skill:
        g_.skills.push_back(d.name.name);
        break;
      default:
        break;
    }
  }

  std::optional<ir::Expr> lowerBoundExpr(const Expr* e, Ctx& ctx) {
    if (e == nullptr) return std::nullopt;
    return lower(e, ctx);
  }

  ir::Domain lowerDomain(const VarDecl& v, Ctx& ctx) {
    ir::Domain d;
    const Expr* e = v.domain.get();
    if (e == nullptr) return d;
    if (e->kind == ExprKind::Range) {
      d.bounds.push_back({lower(e->operands[0].get(), ctx), lower(e->operands[1].get(), ctx)});
    } else if (e->kind == ExprKind::Call) {  // box(x:, y:, yaw:/z:)
      const Type* t = v.type.resolved;
      std::vector<std::string> order = t->kind == TypeKind::SE2 ? std::vector<std::string>{"x", "y", "yaw"}
                                                                : std::vector<std::string>{"x", "y", "z"};
      if (t->kind == TypeKind::Vec) order.resize(static_cast<std::size_t>(std::min(3, t->size)));
      for (const auto& name : order) {
        ir::Bound b;
        for (const auto& a : e->args) {
          if (a.name.name == name && a.value->kind == ExprKind::Range) {
            b.lo = lower(a.value->operands[0].get(), ctx);
            b.hi = lower(a.value->operands[1].get(), ctx);
          }
        }
        d.bounds.push_back(std::move(b));
      }
    } else if (e->kind == ExprKind::List && v.type.resolved->kind == TypeKind::Vec) {
      for (const auto& r : e->operands) {
        d.bounds.push_back({lower(r->operands[0].get(), ctx), lower(r->operands[1].get(), ctx)});
      }
    } else {
      d.set = lower(e, ctx);
    }
    return d;
  }

  void reportEmptyRange(const VarDecl& v, const ir::Domain& d) {
    for (const auto& b : d.bounds) {
      if (b.lo && b.hi && b.lo->op == ir::Op::Num && b.hi->op == ir::Op::Num && b.lo->number > b.hi->number) {
        diags_.error("E0311", v.domain->range,
                     fmt::format("the domain of '{}' is empty: {} > {}", v.name.name, b.lo->number, b.hi->number));
      }
    }
  }

  void lowerVar(const VarDecl& v, Ctx& ctx, std::vector<ir::VarId>& out) {
    std::vector<std::pair<std::string, std::optional<CVal>>> members;
    if (v.index) {
      bool tooLarge = false;
      auto values = enumerate(v.index->set.get(), ctx, &tooLarge);
      if (!values && tooLarge) {
        tooManyMembers(v.index->set->range, "a variable family");
        return;
      }
      if (!values) {
        diags_.error("E0305", v.index->set->range, "the index set of a variable family must be known at compile time");
        return;
      }
      std::set<std::string> seen;
      for (const auto& val : *values) {
        if (!seen.insert(val.text).second) {
          diags_.error("E0202", v.index->set->range,
                       fmt::format("'{}[{}]' is declared twice: the index set lists {} more than once", v.name.name,
                                   val.text, val.text));
          return;
        }
        members.emplace_back(val.text, val);
      }
    } else {
      members.emplace_back("", std::nullopt);
    }
    bool firstMember = true;
    for (const auto& [member, val] : members) {
      ir::Variable var;
      var.id = static_cast<ir::VarId>(g_.variables.size());
      var.name = ctx.prefix + v.name.name + (member.empty() ? "" : "[" + member + "]");
      var.type = typeDesc(v.type.resolved);
      // Domains and initial values read only constants and observations (checked by check-types), so
      // they are lowered in an empty context rather than a copy of one that grows with every variable.
      Ctx inner;
      inner.scope = ctx.scope;
      inner.prefix = ctx.prefix;
      var.domain = lowerDomain(v, inner);
      if (firstMember) reportEmptyRange(v, var.domain);  // once per declaration, not per member
      firstMember = false;
      if (v.init) var.init = lower(v.init.get(), inner);
      std::size_t units = 1 + (var.init ? nodeCount(*var.init) : 0) + (var.domain.set ? nodeCount(*var.domain.set) : 0);
      for (const auto& b : var.domain.bounds) units += (b.lo ? nodeCount(*b.lo) : 0) + (b.hi ? nodeCount(*b.hi) : 0);
      if (!grow(units, v.range)) return;
      if (!member.empty()) {
        var.family = ctx.prefix + v.name.name;
        var.indexText = member;
      }
      var.scope = ctx.scope;
      var.span = span(v.range);
      ctx.vars[&v][member] = var.id;
      out.push_back(var.id);
      g_.variables.push_back(std::move(var));
      declOf_.push_back(&v);
    }
  }

  static bool readsObservation(const ir::Expr& e) {
    if (e.op == ir::Op::Obs) return true;
    for (const auto& c : e.children)
      if (readsObservation(c)) return true;
    return false;
  }

  // `var in set` or, with a field, `var.field in set` (set: a range or a set expression).
  static ir::Expr domainTest(const ir::Variable& var, const std::optional<std::string>& field, ir::Expr set) {
    ir::Expr ref;
    ref.op = ir::Op::Var;
    ref.type = var.type;
    ref.text = var.name;
    ref.id = static_cast<std::int64_t>(var.id);
    if (field) {
      ir::Expr member;
      member.op = ir::Op::Member;
      member.type.kind = ir::TypeKind::Real;
      member.type.spelling = "real";
      member.text = *field;
      member.children.push_back(std::move(ref));
      ref = std::move(member);
    }
    ir::Expr in;
    in.op = ir::Op::In;
    in.type.kind = ir::TypeKind::Bool;
    in.type.spelling = "bool";
    in.children.push_back(std::move(ref));
    in.children.push_back(std::move(set));
    return in;
  }

  std::uint32_t addConstraint(std::string name, ir::Expr expr, const std::string& scope, SourceRange at) {
    grow(1 + nodeCount(expr), at);
    ir::Constraint c;
    c.id = static_cast<std::uint32_t>(g_.constraints.size());
    c.name = std::move(name);
    std::set<ir::VarId> vars;
    collectVars(expr, vars);
    c.vars.assign(vars.begin(), vars.end());
    c.expr = std::move(expr);
    c.scope = scope;
    c.span = span(at);
    g_.constraints.push_back(std::move(c));
    return g_.constraints.back().id;
  }

  // Unrolls nested top-level foralls over compile-time sets. `instances` is the number of copies the
  // enclosing levels already make; a level that would take the total past kMaxUnrolled keeps its quantifier.
  // Binder values are set in ctx.env for the body and removed again, so no context is copied per binding.
  void lowerRequire(const RequireDecl& r, Ctx& ctx, std::vector<std::uint32_t>& out, const std::string& base,
                    const Expr* cond, std::string suffix, std::size_t instances = 1) {
    if (cond->kind == ExprKind::Quantifier && cond->quant == QuantKind::Forall && !cond->binder->names.empty()) {
      auto values = enumerate(cond->binder->set.get(), ctx);
      const auto& names = cond->binder->names;
      std::size_t total = instances;
      for (std::size_t i = 0; values && i < names.size() && total <= kMaxUnrolled; ++i)
        total *= std::max<std::size_t>(1, values->size());
      if (values && total <= kMaxUnrolled) {
        if (values->empty()) return;  // vacuously true: no instance
        std::vector<std::size_t> pos(names.size(), 0);
        while (!tooLarge_) {
          std::string binding;
          for (std::size_t i = 0; i < names.size(); ++i) {
            ctx.env[names[i].get()] = (*values)[pos[i]];
            binding += (i ? "," : "") + (*values)[pos[i]].text;
          }
          const Expr* where = cond->operands[0].get();
          auto decided = decide(where, ctx);
          if (!decided || *decided) {
            const std::string s = suffix + "[" + binding + "]";
            if (decided) {
              lowerRequire(r, ctx, out, base, cond->operands[1].get(), s, total);
            } else {
              ir::Expr imp;
              imp.op = ir::Op::Implies;
              imp.type = {ir::TypeKind::Bool, "bool"};
              imp.children.push_back(lower(where, ctx));
              imp.children.push_back(lower(cond->operands[1].get(), ctx));
              out.push_back(addConstraint(base + s, std::move(imp), ctx.scope, r.range));
            }
          }
          // Next binding: the last binder varies fastest.
          std::size_t k = names.size();
          while (k > 0 && ++pos[k - 1] == values->size()) pos[--k] = 0;
          if (k == 0) break;
        }
        for (const auto& n : names) ctx.env.erase(n.get());
        return;
      }
    }
    out.push_back(addConstraint(base + suffix, lower(cond, ctx), ctx.scope, r.range));
  }

  void lowerSample(const SampleDecl& s, Ctx& ctx, std::vector<std::uint32_t>& out) {
    if (!s.forBinder) {
      lowerSampleInstance(s, ctx, out);
      return;
    }
    bool tooLarge = false;
    auto values = enumerate(s.forBinder->set.get(), ctx, &tooLarge);
    if (!values && tooLarge) {
      tooManyMembers(s.forBinder->set->range, "the 'for' set of a sample statement");
      return;
    }
    if (!values) {
      diags_.error("E0305", s.forBinder->set->range,
                   "the 'for' set of a sample statement must be known at compile time");
      return;
    }
    // One sampler per member; the binder's value is set in ctx.env for each and removed afterwards.
    for (const auto& v : *values) {
      if (tooLarge_) break;
      for (const auto& n : s.forBinder->names) ctx.env[n.get()] = v;
      lowerSampleInstance(s, ctx, out);
    }
    for (const auto& n : s.forBinder->names) ctx.env.erase(n.get());
  }

  void lowerSampleInstance(const SampleDecl& s, Ctx& inner, std::vector<std::uint32_t>& out) {
    ir::Sampler smp;
    smp.id = static_cast<std::uint32_t>(g_.samplers.size());
    smp.sampler = s.sampler.name;
    std::set<ir::VarId> writes, reads;
    for (const auto& t : s.targets) {
      if (t->kind == ExprKind::Name && t->ref.kind == RefKind::Variable) {
        for (const auto& [m, id] : lookupVars(t->ref.decl, inner)) writes.insert(id);
      } else {
        collectVars(lower(t.get(), inner), writes);
      }
    }
    const auto* callee =
        s.samplerRef.kind == RefKind::Sampler ? static_cast<const CallableDecl*>(s.samplerRef.decl) : nullptr;
    std::size_t units = 1;
    for (const auto* a : orderedArgs(callee, s.args)) {
      smp.args.push_back(lower(a->value.get(), inner));
      collectVars(smp.args.back(), reads);
      units += nodeCount(smp.args.back());
    }
    if (!grow(units, s.range)) return;
    smp.writes.assign(writes.begin(), writes.end());
    smp.reads.assign(reads.begin(), reads.end());
    smp.scope = inner.scope;
    smp.span = span(s.range);
    out.push_back(smp.id);
    g_.samplers.push_back(std::move(smp));
  }

  void lowerBody(const std::vector<const Decl*>& body, Ctx& ctx, std::vector<ir::VarId>& vars,
                 std::vector<std::uint32_t>& constraints, std::vector<std::uint32_t>& samplers,
                 std::vector<std::uint32_t>& costs) {
    const std::size_t firstVar = vars.size();
    for (const Decl* d : body) {
      if (d->kind == DeclKind::Var) lowerVar(static_cast<const VarDecl&>(*d), ctx, vars);
    }
    // Domains the solver's samplers alone cannot keep become constraints named `<var>.domain`, which a graph
    // dump shows and the solver checks like any other: a domain read from an observation (`var book : Book
    // in pickable`) changes from one CSP to the next, and an initial value read from an observation
    // (`= plateXY`) may lie outside the declared domain, while the solver tries the initial values first.
    for (std::size_t i = firstVar; i < vars.size(); ++i) {
      const ir::Variable& var = g_.variables[vars[i]];
      const bool observedSet = var.domain.set && var.domain.set->op == ir::Op::Obs;
      const bool observedInit = var.init && readsObservation(*var.init);
      std::optional<ir::Expr> cond;
      if (observedSet || (observedInit && var.domain.set)) {
        cond = domainTest(var, std::nullopt, *var.domain.set);
      } else if (observedInit && !var.domain.bounds.empty()) {
        static const std::vector<std::string> kVec = {"x", "y", "z"}, kSe2 = {"x", "y", "yaw"};
        const std::vector<std::string>& fields = var.type.kind == ir::TypeKind::SE2 ? kSe2 : kVec;
        for (std::size_t c = 0; c < var.domain.bounds.size(); ++c) {
          const ir::Bound& b = var.domain.bounds[c];
          if (!b.lo || !b.hi) continue;  // a one-sided bound cannot be written as a range test
          if (var.domain.bounds.size() > 1 && c >= fields.size()) break;
          ir::Expr range;
          range.op = ir::Op::Range;
          range.type.kind = ir::TypeKind::Range;
          range.type.spelling = "range";
          range.children = {*b.lo, *b.hi};
          std::optional<std::string> field;
          if (var.domain.bounds.size() > 1) field = fields[c];
          ir::Expr test = domainTest(var, field, std::move(range));
          if (!cond) {
            cond = std::move(test);
          } else {
            ir::Expr both;
            both.op = ir::Op::And;
            both.type = test.type;
            both.children.push_back(std::move(*cond));
            both.children.push_back(std::move(test));
            cond = std::move(both);
          }
        }
      }
      if (!cond) continue;
      constraints.push_back(addConstraint(var.name + ".domain", std::move(*cond), var.scope, declOf_[var.id]->range));
    }
    std::size_t anonymous = 0;
    for (const Decl* d : body) {
      if (d->kind == DeclKind::Require) {
        const auto& r = static_cast<const RequireDecl&>(*d);
        const std::string base =
            ctx.prefix + (r.name.name.empty() ? fmt::format("require#{}", ++anonymous) : r.name.name);
        lowerRequire(r, ctx, constraints, base, r.condition.get(), "");
      } else if (d->kind == DeclKind::Sample) {
        lowerSample(static_cast<const SampleDecl&>(*d), ctx, samplers);
      } else if (d->kind == DeclKind::Cost) {
        const auto& c = static_cast<const CostDecl&>(*d);
        ir::Cost cost;
        cost.maximize = c.maximize;
        cost.expr = lower(c.value.get(), ctx);
        std::set<ir::VarId> vs;
        collectVars(cost.expr, vs);
        cost.vars.assign(vs.begin(), vs.end());
        cost.span = span(c.range);
        if (!grow(1 + nodeCount(cost.expr), c.range)) continue;
        costs.push_back(static_cast<std::uint32_t>(g_.costs.size()));
        g_.costs.push_back(std::move(cost));
      }
    }
  }

  static std::vector<const Decl*> raw(const std::vector<std::unique_ptr<Decl>>& body) {
    std::vector<const Decl*> out;
    for (const auto& d : body) out.push_back(d.get());
    return out;
  }

  ir::Action lowerAction(const ActionStmt& s, Ctx& ctx) {
    ir::Action a;
    a.span = span(s.range);
    switch (s.kind) {
      case ActionStmtKind::Call: {
        a.kind = ir::ActionKind::Call;
        a.name = s.callee.name;
        const auto* callee =
            s.calleeRef.kind == RefKind::Action ? static_cast<const CallableDecl*>(s.calleeRef.decl) : nullptr;
        for (const auto* arg : orderedArgs(callee, s.args)) a.args.push_back(lower(arg->value.get(), ctx));
        break;
      }
      case ActionStmtKind::For:
        a.kind = ir::ActionKind::For;
        for (const auto& n : s.forBinder->names) a.binders.push_back(n->name.name);
        a.set = lower(s.forBinder->set.get(), ctx);
        for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
        break;
      case ActionStmtKind::If:
        a.kind = ir::ActionKind::If;
        a.condition = lower(s.condition.get(), ctx);
        for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
        for (const auto& b : s.elseBody) a.elseBody.push_back(lowerAction(*b, ctx));
        break;
      case ActionStmtKind::Block:
        a.kind = ir::ActionKind::Block;
        for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
        break;
    }
    return a;
  }

  void lowerTask(const TaskDecl& t, std::set<std::string>& usedSkills) {
    ir::Task task;
    task.name = t.name.name;
    task.span = span(t.range);
    task.vars = globalVars_;
    task.constraints = globalConstraints_;
    task.samplers = globalSamplers_;
    task.costs = globalCosts_;
    Ctx ctx;
    ctx.scope = "task:" + t.name.name;
    lowerBody(raw(t.body), ctx, task.vars, task.constraints, task.samplers, task.costs);
    for (const auto& inst : t.instances) {
      if (tooLarge_) break;
      if (inst.skillDecl == nullptr) continue;
      usedSkills.insert(inst.skill.name);
      ir::SkillInstance si;
      si.skill = inst.skill.name;
      si.name = inst.instanceName();
      si.span = span(inst.range);
      Ctx sctx;
      sctx.scope = fmt::format("skill:{}/{}", t.name.name, si.name);
      sctx.prefix = si.name + ".";
      sctx.skill = inst.skillDecl;
      for (const auto& a : inst.args) {
        ir::Expr x = lower(a.value.get(), ctx);
        if (x.op == ir::Op::Var) si.params.push_back(static_cast<ir::VarId>(x.id));
        sctx.skillParams.push_back(std::move(x));
      }
      std::vector<ir::VarId> vars;
      std::vector<std::uint32_t> constraints, samplers, costs;
      lowerBody(raw(inst.skillDecl->body), sctx, vars, constraints, samplers, costs);
      for (const auto& a : inst.skillDecl->actions) {
        si.actions.push_back(lowerAction(*a, sctx));
        grow(actionSize(si.actions.back()), a->range);
      }
      task.vars.insert(task.vars.end(), vars.begin(), vars.end());
      task.constraints.insert(task.constraints.end(), constraints.begin(), constraints.end());
      task.samplers.insert(task.samplers.end(), samplers.begin(), samplers.end());
      task.costs.insert(task.costs.end(), costs.begin(), costs.end());
      si.vars = std::move(vars);
      si.constraints = std::move(constraints);
      si.samplers = std::move(samplers);
      task.instances.push_back(std::move(si));
    }
    g_.tasks.push_back(std::move(task));
  }

  // --- generators ---------------------------------------------------------------------------

  static double constNumber(const Expr* e) {
    if (e == nullptr) return 0;
    if (e->kind == ExprKind::Unary && e->unaryOp == UnaryOp::Neg) return -constNumber(e->operands[0].get());
    return e->number;
  }

  void lowerGenerator(const PersonalDecl& p) {
    ir::Generator g;
    g.name = p.name.name;
    g.span = span(p.range);
    for (const auto& prm : p.params) g.params.push_back({prm.name.name, typeDesc(prm.type.resolved)});
    for (const auto& pat : p.patterns) {
      g.patterns.push_back({pat.param.name, static_cast<std::uint32_t>(std::max(0, pat.paramIndex)),
                            pat.kind == PatternKind::Glob ? ir::PatternKind::Glob : ir::PatternKind::Regex, pat.pattern,
                            span(pat.patternRange)});
    }
    for (const auto& c : p.captures) g.captures.push_back(c.name);
    for (const auto& k : p.perKeys) g.perKeys.push_back(k.name);
    Ctx none;
    for (const auto& f : p.factors) {
      ir::ModelFactor mf;
      mf.label = generatorFactorName(p, f);
      // The generator checker accepts only the kinds, directions, scales and ratings OpNames spells.
      mf.kind = ir::factorKindFromName(f.kind.name).value_or(ir::FactorKind::Interval);
      mf.span = span(f.range);
      std::vector<const Arg*> positional;
      for (const auto& a : f.args) {
        if (a.name.name.empty())
          positional.push_back(&a);
        else if (a.name.name == "prompt")
          mf.prompt = a.value->text;
        else if (a.name.name == "learning")
          mf.learning = a.value->text;
        else if (a.name.name == "scale")
          mf.scale = ir::textScaleFromName(a.value->text).value_or(ir::TextScale::Absolute);
        else if (a.name.name == "rating")
          mf.rating = ir::textRatingFromName(a.value->text).value_or(ir::TextRating::Digits);
      }
      if (!positional.empty()) {
        mf.feature = lower(positional[0]->value.get(), none);
        for (int i : paramsRead(positional[0]->value.get())) mf.params.push_back(p.params[i].name.name);
      }
      if (positional.size() >= 2 && positional[1]->value->kind == ExprKind::Range) {
        mf.lo = constNumber(positional[1]->value->operands[0].get());
        mf.hi = constNumber(positional[1]->value->operands[1].get());
      }
      if (positional.size() >= 3)
        mf.direction =
            ir::thresholdDirectionFromName(positional[2]->value->text).value_or(ir::ThresholdDirection::None);
      g.factors.push_back(std::move(mf));
    }
    for (const auto& c : p.guards) {
      ir::Expr e = lower(c.get(), none);
      if (!g.guard) {
        g.guard = std::move(e);
      } else {
        ir::Expr both;
        both.op = ir::Op::And;
        both.type = e.type;
        both.children.push_back(std::move(*g.guard));
        both.children.push_back(std::move(e));
        g.guard = std::move(both);
      }
    }
    if (!p.accepts.empty()) g.accept = p.accepts[0]->number;
    if (!p.fallbacks.empty()) g.fallback = p.fallbacks[0]->number;
    for (const auto& rule : p.learnRules) {
      ir::LearnRule r;
      r.event = rule.event.name;
      r.span = span(rule.range);
      for (const auto& b : rule.binders) {
        const std::string& n = b->name.name;
        r.binders.push_back(n.empty() ? "_" : n);
        bool binds = false;
        for (const auto& prm : p.params) binds = binds || prm.name.name == n;
        for (const auto& c : p.captures) binds = binds || c.name == n;
        r.binds.push_back(binds && !n.empty() ? n : "");
      }
      for (const auto& l : rule.labels) r.labels.push_back({l.factor.name, lower(l.value.get(), none)});
      if (rule.condition) r.condition = lower(rule.condition.get(), none);
      g.learnRules.push_back(std::move(r));
    }
    warnIfUnmatched(p, g);
    g_.generators.push_back(std::move(g));
  }

  // W0401: some parameter's pattern (with its type) matches no variable of any task.
  void warnIfUnmatched(const PersonalDecl& p, const ir::Generator& g) {
    for (std::size_t i = 0; i < p.params.size(); ++i) {
      const ir::TypeDesc want = g.params[i].type;
      const PatternClause* pat = nullptr;
      for (const auto& pc : p.patterns) {
        if (pc.paramIndex == static_cast<int>(i)) pat = &pc;
      }
      std::optional<GlobPattern> glob;
      std::optional<std::regex> re;
      std::string error;
      std::size_t at = 0;
      if (pat && pat->kind == PatternKind::Glob) glob = parseGlob(pat->pattern, error, at);
      if (pat && pat->kind == PatternKind::Regex) re = compileRegex(pat->pattern, error);
      bool any = false;
      for (const auto& v : g_.variables) {
        if (v.type.spelling != want.spelling) continue;
        std::map<std::string, std::string> b;
        if (pat == nullptr || (glob && matchGlob(*glob, v.name, b)) || (re && std::regex_match(v.name, *re))) {
          any = true;
          break;
        }
      }
      if (!any) {
        Diagnostic& d =
            diags_.warning("W0401", pat ? pat->patternRange : p.params[i].name.range,
                           fmt::format("no {} variable of any task matches parameter '{}' of generator '{}'",
                                       want.spelling, p.params[i].name.name, p.name.name));
        d.help("`cbtlc emit FILE` lists every variable's name and type");
      }
    }
  }

  const GlobalSymbols& symbols_;
  const SourceManager& sources_;
  DiagnosticEngine& diags_;
  ir::ConstraintGraph& g_;
  Ctx globalCtx_;
  std::vector<std::pair<std::size_t, const CallableDecl*>> pendingBodies_;  // function index, its declaration
  std::size_t graphSize_ = 0;
  bool tooLarge_ = false;
  std::vector<const VarDecl*> declOf_;  // the declaration of each graph variable, by id
  std::vector<ir::VarId> globalVars_;
  std::vector<std::uint32_t> globalConstraints_, globalSamplers_, globalCosts_;
};

}  // namespace

bool lowerToGraph(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                  const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& graph) {
  const std::size_t before = diags.errorCount();
  Lowerer(symbols, sources, diags, graph).run(modules);
  return diags.errorCount() == before;
}

}  // namespace cbtl
