#include "runtime/core/ProgramCompiler.h"

#include "ir/OpNames.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace cbtl::rt {

namespace {

// The pool operator of an IR binary operator (ir::isBinary).
Op poolOp(ir::Op op) {
  switch (op) {
    case ir::Op::Add:
      return Op::Add;
    case ir::Op::Sub:
      return Op::Sub;
    case ir::Op::Mul:
      return Op::Mul;
    case ir::Op::Div:
      return Op::Div;
    case ir::Op::Mod:
      return Op::Mod;
    case ir::Op::Pow:
      return Op::Pow;
    case ir::Op::Eq:
      return Op::Eq;
    case ir::Op::Ne:
      return Op::Ne;
    case ir::Op::Lt:
      return Op::Lt;
    case ir::Op::Le:
      return Op::Le;
    case ir::Op::Gt:
      return Op::Gt;
    case ir::Op::Ge:
      return Op::Ge;
    case ir::Op::And:
      return Op::And;
    case ir::Op::Or:
      return Op::Or;
    case ir::Op::Implies:
      return Op::Implies;
    default:  // Iff, the last binary operator; nothing else reaches here
      return Op::Iff;
  }
}

std::uint16_t atLeastOne(std::uint16_t width) { return std::max<std::uint16_t>(width, 1); }

}  // namespace

std::string ProgramCompiler::at() const { return span_ != nullptr ? Program::where(*span_) : ""; }

double ProgramCompiler::memberIndex(const std::string& typeName, const std::string& member) const {
  if (const auto index = program_.memberIndex(typeName, member)) return *index;
  throw RuntimeError(at(), fmt::format("'{}' is not a member of '{}'", member, typeName));
}

std::uint32_t ProgramCompiler::constNode(std::vector<double> values, std::uint16_t width) {
  values.resize(width, 0.0);
  Node n;
  n.op = Op::Const;
  n.width = width;
  n.a = program_.pool_.addConstants(values);
  return program_.pool_.add(std::move(n));
}

// --- constants and sets -------------------------------------------------------------------------------

std::vector<double> ProgramCompiler::constantValue(const ir::Expr& e) {
  Scope scope;
  std::uint32_t top = 0;
  scope.frameTop = &top;
  const std::uint32_t node = compile(e, scope);
  std::vector<double> frame(top + 1, 0.0);
  EvalContext ctx{nullptr, nullptr, frame.data(), program_.callContext()};
  std::vector<double> out(std::max<std::size_t>(program_.pool_.width(node), 1));
  program_.pool_.eval(node, ctx, out.data());
  return out;
}

std::vector<std::string> ProgramCompiler::constantStrings(const ir::Expr& e) {
  const ValueType t = program_.typeOf(e.type);
  std::vector<std::string> out;
  if (t.kind == ValueKind::Set) {
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    ValueType elem;
    for (double m : setMembers(e, elem, scope)) out.push_back(program_.render(elem, &m));
    return out;
  }
  const auto v = constantValue(e);
  out.push_back(program_.render(t, v.data()));
  return out;
}

std::vector<double> ProgramCompiler::setMembers(const ir::Expr& set, ValueType& elem, Scope& scope) {
  std::vector<double> out;
  switch (set.op) {
    case ir::Op::EnumSet: {
      const auto* e = program_.findEnum(set.text);
      elem = ValueType{ValueKind::Enum, 1, set.text};
      for (std::size_t i = 0; e != nullptr && i < e->members.size(); ++i) out.push_back(static_cast<double>(i));
      return out;
    }
    case ir::Op::ItemSet: {
      const auto* s = program_.findItemSet(set.text);
      elem = ValueType{ValueKind::Item, 1, s != nullptr ? s->itemType : set.text};
      for (std::size_t i = 0; s != nullptr && i < s->entries.size(); ++i) out.push_back(static_cast<double>(i));
      return out;
    }
    case ir::Op::Const:
      if (const ir::Constant* c = program_.findConstant(set.text); c != nullptr && set.children.empty())
        return setMembers(c->value, elem, scope);
      break;
    case ir::Op::List:
      for (const auto& c : set.children) {
        const auto v = constantValue(c);
        elem = program_.typeOf(c.type);
        out.push_back(v.empty() ? 0 : v[0]);
      }
      return out;
    default:
      break;
  }
  throw RuntimeError(at(), fmt::format("a set given by '{}' is not supported at run time (use an enum, item set or "
                                       "constant list)",
                                       ir::name(set.op)));
}

// --- expressions --------------------------------------------------------------------------------------

std::uint32_t ProgramCompiler::compile(const ir::Expr& e, Scope& scope) {
  const std::uint32_t node = compileNode(e, scope);
  ExprPool& pool = program_.pool_;
  if (pool.width(node) > kMaxValueWidth) {
    throw RuntimeError(
        at(),
        fmt::format("a value of {} doubles ('{}' of type {}) is wider than the runtime's limit of {}", pool.width(node),
                    e.text.empty() ? std::string(ir::name(e.op)) : e.text, e.type.spelling, kMaxValueWidth));
  }
  const PackedNode& packed = pool.node(node);
  if ((packed.op == Op::TableVar || packed.op == Op::TableObs || packed.op == Op::TableConst) && packed.count == 0) {
    throw RuntimeError(at(), fmt::format("'{}' indexes an empty family", e.text));
  }
  if (scope.frameTop != nullptr) program_.frameSize_ = std::max<std::size_t>(program_.frameSize_, *scope.frameTop);
  return node;
}

std::uint32_t ProgramCompiler::compileNode(const ir::Expr& e, Scope& scope) {
  switch (e.op) {
    case ir::Op::Num:
    case ir::Op::Bool:
      return constNode({e.number}, 1);
    case ir::Op::Str:
      return constNode({static_cast<double>(program_.strings().intern(e.text))}, 1);
    case ir::Op::Enum:
    case ir::Op::Item:
      return constNode({memberIndex(e.extra, e.text)}, 1);
    case ir::Op::Var:
      return compileVar(e);
    case ir::Op::Param:
      return compileParam(e, scope);
    case ir::Op::Local:
      return compileLocal(e, scope);
    case ir::Op::Const:
      return compileConstRef(e, scope);
    case ir::Op::Obs:
      return compileObservation(e, scope);
    case ir::Op::Family:
      return compileFamily(e, scope);
    case ir::Op::Member:
      return compileMember(e, scope);
    case ir::Op::Neg:
    case ir::Op::Not:
      return compileUnary(e, scope);
    case ir::Op::Add:
    case ir::Op::Sub:
    case ir::Op::Mul:
    case ir::Op::Div:
    case ir::Op::Mod:
    case ir::Op::Pow:
    case ir::Op::Eq:
    case ir::Op::Ne:
    case ir::Op::Lt:
    case ir::Op::Le:
    case ir::Op::Gt:
    case ir::Op::Ge:
    case ir::Op::And:
    case ir::Op::Or:
    case ir::Op::Implies:
    case ir::Op::Iff:
      return compileBinary(e, scope);
    case ir::Op::In:
      return compileIn(e, scope);
    case ir::Op::If:
      return compileIf(e, scope);
    case ir::Op::Call:
      return compileCall(e, scope);
    case ir::Op::Forall:
    case ir::Op::Exists:
      return compileQuantifier(e, scope, 0);
    case ir::Op::Tuple:
      return compileTuple(e, scope);
    case ir::Op::EnumSet:  // sets only as the right of `in`, a quantifier's or a domain's set
    case ir::Op::ItemSet:
    case ir::Op::Range:
    case ir::Op::List:
    case ir::Op::Index:  // indexing other than of a family
    case ir::Op::Invalid:
      break;
  }
  throw RuntimeError(at(), fmt::format("expression '{}' is not supported at run time", ir::name(e.op)));
}

std::uint32_t ProgramCompiler::compileVar(const ir::Expr& e) {
  if (e.id < 0 || static_cast<std::size_t>(e.id) >= program_.graph().variables.size())
    throw RuntimeError(at(), fmt::format("unknown variable '{}'", e.text));
  const VarSlot& s = program_.slot(static_cast<ir::VarId>(e.id));
  return program_.pool_.add(Node{Op::ReadVar, s.type.width, s.offset, 0, 0, nullptr, {}, {}});
}

std::uint32_t ProgramCompiler::compileParam(const ir::Expr& e, Scope& scope) {
  if (e.id < 0 || static_cast<std::size_t>(e.id) >= scope.params.size() ||
      scope.params[static_cast<std::size_t>(e.id)] == UINT32_MAX) {
    // A learning rule's labels and condition see only the parameters its event binds.
    throw RuntimeError(
        at(),
        fmt::format("parameter '{}' is not bound here (a learning rule must bind every parameter it reads)", e.text));
  }
  return scope.params[static_cast<std::size_t>(e.id)];
}

std::uint32_t ProgramCompiler::compileLocal(const ir::Expr& e, Scope& scope) {
  auto it = scope.locals.find(e.text);
  if (it == scope.locals.end()) throw RuntimeError(at(), fmt::format("'{}' is not bound here", e.text));
  const ValueType t = program_.typeOf(e.type);
  return program_.pool_.add(Node{Op::ReadFrame, atLeastOne(t.width), it->second, 0, 0, nullptr, {}, {}});
}

std::uint32_t ProgramCompiler::compileConstRef(const ir::Expr& e, Scope& scope) {
  const ir::Constant* c = program_.findConstant(e.text);
  if (c == nullptr) throw RuntimeError(at(), fmt::format("unknown constant '{}'", e.text));
  const ValueType t = program_.typeOf(e.type);
  if (e.children.empty()) return constNode(constantValue(c->value), t.width);
  // A constant family indexed at run time: one table entry per member of the index set.
  if (c->value.op != ir::Op::List)
    throw RuntimeError(Program::where(c->span), fmt::format("constant family '{}' must be a list", c->name));
  std::vector<std::uint32_t> offsets;
  for (const auto& elemExpr : c->value.children) {
    auto v = constantValue(elemExpr);
    v.resize(t.width, 0.0);
    offsets.push_back(program_.pool_.addConstants(v));
  }
  Node n;
  n.op = Op::TableConst;
  n.width = t.width;
  n.count = static_cast<std::uint32_t>(offsets.size());
  n.a = program_.pool_.addTable(offsets);
  n.kids.push_back(compile(e.children[0], scope));
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileObservation(const ir::Expr& e, Scope& scope) {
  ExprPool& pool = program_.pool_;
  if (e.children.empty()) {
    const auto& slots = program_.observationSlots();
    auto slot = slots.find(e.text);
    if (slot == slots.end()) throw RuntimeError(at(), fmt::format("unknown observation '{}'", e.text));
    return pool.add(Node{Op::ReadObs, slot->second.type.width, slot->second.offset, 0, 0, nullptr, {}, {}});
  }
  const ir::Observation* decl = program_.findObservation(e.text);
  if (decl == nullptr || !decl->indexSet)
    throw RuntimeError(at(), fmt::format("'{}' is not an observation family", e.text));
  ValueType elem;
  Scope none;
  std::uint32_t top = 0;
  none.frameTop = &top;
  const auto members = setMembers(*decl->indexSet, elem, none);
  std::vector<std::uint32_t> offsets;
  for (double m : members) {
    const std::string key = e.text + "[" + program_.render(elem, &m) + "]";
    offsets.push_back(program_.observationSlots().at(key).offset);
  }
  const ValueType t = program_.typeOf(e.type);
  Node n{Op::TableObs, t.width, pool.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr, {}, {}};
  n.kids.push_back(compile(e.children[0], scope));
  return pool.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileFamily(const ir::Expr& e, Scope& scope) {
  // e.vars holds the members in no particular order: map each to its index by the member's name.
  const ir::Expr& index = e.children[0];
  const ValueType it = program_.typeOf(index.type);
  std::vector<std::pair<double, ir::VarId>> byIndex;
  for (ir::VarId v : e.vars) {
    const auto& var = program_.graph().variables.at(v);
    const double idx = it.kind == ValueKind::Int ? std::stod(var.indexText) : memberIndex(it.typeName, var.indexText);
    byIndex.emplace_back(idx, v);
  }
  std::sort(byIndex.begin(), byIndex.end());
  std::vector<std::uint32_t> offsets;
  double first = byIndex.empty() ? 0 : byIndex.front().first;
  for (std::size_t i = 0; i < byIndex.size(); ++i) {
    if (byIndex[i].first != first + static_cast<double>(i))
      throw RuntimeError(at(), fmt::format("family '{}' has gaps in its index", e.text));
    offsets.push_back(program_.slot(byIndex[i].second).offset);
  }
  ExprPool& pool = program_.pool_;
  std::uint32_t idxNode = compile(index, scope);
  if (first != 0) idxNode = pool.add(Node{Op::Sub, 1, 0, 0, 0, nullptr, {idxNode, constNode({first}, 1)}, {}});
  const ValueType t = program_.typeOf(e.type);
  Node n{Op::TableVar, t.width, pool.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr,
         {idxNode},    {}};
  return pool.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileMember(const ir::Expr& e, Scope& scope) {
  const ir::Expr& base = e.children[0];
  const ValueType bt = program_.typeOf(base.type);
  const std::uint32_t baseNode = compile(base, scope);
  const std::uint16_t width = atLeastOne(program_.typeOf(e.type).width);
  ExprPool& pool = program_.pool_;
  if (bt.kind == ValueKind::Item) {
    // A field of an item: one constant per entry of the item type's set, indexed by the item.
    const auto* items = program_.findItemSetOfType(bt.typeName);
    if (items == nullptr) throw RuntimeError(at(), fmt::format("no item set of type '{}'", bt.typeName));
    std::vector<std::uint32_t> offsets;
    for (const auto& entry : items->entries) {
      std::vector<double> v(width, 0.0);
      for (const auto& [field, value] : entry.fields) {
        if (field == e.text) v = constantValue(value);
      }
      v.resize(width, 0.0);
      offsets.push_back(pool.addConstants(v));
    }
    Node n{Op::TableConst, width, pool.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr,
           {baseNode},     {}};
    return pool.add(std::move(n));
  }
  // A component of a vector or pose.
  const std::string& m = e.text;
  std::uint32_t offset = 0;
  if (bt.kind == ValueKind::SE3 && m == "position")
    offset = 0;
  else if (bt.kind == ValueKind::SE3 && m == "orientation")
    offset = 3;
  else if (m == "x")
    offset = 0;
  else if (m == "y")
    offset = 1;
  else if (m == "z" || (bt.kind == ValueKind::SE2 && m == "yaw"))
    offset = 2;
  else if (m == "w")
    offset = 3;
  else
    throw RuntimeError(at(), fmt::format("member '{}' of {} is not supported at run time", m, toString(bt.kind)));
  return pool.add(Node{Op::Member, width, offset, 0, 0, nullptr, {baseNode}, {}});
}

std::uint32_t ProgramCompiler::compileUnary(const ir::Expr& e, Scope& scope) {
  Node n{e.op == ir::Op::Neg ? Op::Neg : Op::Not,
         atLeastOne(program_.typeOf(e.type).width),
         0,
         0,
         0,
         nullptr,
         {compile(e.children[0], scope)},
         {}};
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileBinary(const ir::Expr& e, Scope& scope) {
  const ValueType t = program_.typeOf(e.type);
  if (e.op == ir::Op::Add && t.kind == ValueKind::Text) {
    Node n{Op::Call, 1, 0, 0, 0, concatTexts, {compile(e.children[0], scope), compile(e.children[1], scope)}, {1, 1}};
    return program_.pool_.add(std::move(n));
  }
  Node n;
  n.op = poolOp(e.op);
  n.width = atLeastOne(t.width);
  n.kids = {compile(e.children[0], scope), compile(e.children[1], scope)};
  // Integer division truncates (b = 1).
  if (n.op == Op::Div && e.children[0].type.kind == ir::TypeKind::Int && e.children[1].type.kind == ir::TypeKind::Int)
    n.b = 1;
  if (n.op >= Op::Eq) n.width = 1;
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileIf(const ir::Expr& e, Scope& scope) {
  Node n{Op::If, atLeastOne(program_.typeOf(e.type).width), 0, 0, 0, nullptr, {}, {}};
  for (const auto& c : e.children) n.kids.push_back(compile(c, scope));
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileTuple(const ir::Expr& e, Scope& scope) {
  Node n{Op::Concat, 0, 0, 0, 0, nullptr, {}, {}};
  std::size_t width = 0;
  for (const auto& c : e.children) {
    n.kids.push_back(compile(c, scope));
    width += program_.pool_.width(n.kids.back());
    if (width > kMaxValueWidth) {
      throw RuntimeError(
          at(), fmt::format("a tuple of more than {} doubles is wider than the runtime's limit", kMaxValueWidth));
    }
  }
  n.width = static_cast<std::uint16_t>(width);
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileCall(const ir::Expr& e, Scope& scope) {
  const ir::Function* f = program_.findFunction(e.text);
  std::vector<std::uint32_t> args;
  for (const auto& c : e.children) args.push_back(compile(c, scope));
  if (f != nullptr && !f->isExtern && f->body) {
    // Inline the body with its parameters bound to the argument nodes (bodies are pure expressions).
    if (++inlineDepth_ > 64) throw RuntimeError(at(), fmt::format("function '{}' expands too deeply", e.text));
    Scope inner;
    inner.params = args;
    inner.frameTop = scope.frameTop;
    const std::uint32_t node = compile(*f->body, inner);
    --inlineDepth_;
    return node;
  }
  if (f != nullptr && f->kind != ir::FunctionKind::Function) {
    throw RuntimeError(
        at(), fmt::format("'{}' is a {} and cannot be called inside an expression", e.text, ir::name(f->kind)));
  }
  FunctionImpl impl = program_.builtins().function(e.text);
  if (impl == nullptr)
    throw RuntimeError(at(), fmt::format("built-in function '{}' has no implementation in this runtime", e.text));
  Node n;
  n.op = Op::Call;
  n.fn = impl;
  n.width = atLeastOne(program_.typeOf(e.type).width);
  n.kids = args;
  std::size_t argsWidth = 0;
  for (std::uint32_t a : args) {
    n.kidWidths.push_back(program_.pool_.width(a));
    argsWidth += program_.pool_.width(a);
  }
  if (argsWidth > kMaxCallArgsWidth) {
    throw RuntimeError(at(), fmt::format("the arguments of '{}' take {} doubles, more than the runtime's limit of {}",
                                         e.text, argsWidth, kMaxCallArgsWidth));
  }
  return program_.pool_.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileIn(const ir::Expr& e, Scope& scope) {
  const ir::Expr& set = e.children[1];
  ExprPool& pool = program_.pool_;
  if (set.op == ir::Op::Range) {
    Node n;
    n.op = Op::InRange;
    n.kids = {compile(e.children[0], scope), compile(set.children[0], scope), compile(set.children[1], scope)};
    return pool.add(std::move(n));
  }
  if (set.op == ir::Op::Obs && set.children.empty()) {
    // An observed set: its membership flags, indexed by the element's member index.
    const auto& slots = program_.observationSlots();
    auto it = slots.find(set.text);
    if (it != slots.end() && it->second.type.kind == ValueKind::Set) {
      std::vector<std::uint32_t> offsets(it->second.type.width);
      for (std::size_t i = 0; i < offsets.size(); ++i) offsets[i] = it->second.offset + static_cast<std::uint32_t>(i);
      Node n;
      n.op = Op::TableObs;
      n.a = pool.addTable(offsets);
      n.count = static_cast<std::uint32_t>(offsets.size());
      n.kids = {compile(e.children[0], scope)};
      return pool.add(std::move(n));
    }
  }
  ValueType elem;
  const auto members = setMembers(set, elem, scope);
  Node n;
  n.op = Op::InSet;
  n.a = pool.addConstants(members);
  n.b = static_cast<std::uint32_t>(members.size());
  n.kids = {compile(e.children[0], scope)};
  return pool.add(std::move(n));
}

std::uint32_t ProgramCompiler::compileQuantifier(const ir::Expr& e, Scope& scope, std::size_t binder) {
  const ir::Expr& set = e.children[0];
  Node n;
  n.op = e.op == ir::Op::Forall ? Op::Forall : Op::Exists;
  n.a = (*scope.frameTop)++;
  const std::string name = e.names[binder];
  std::optional<std::uint32_t> saved;
  if (auto it = scope.locals.find(name); it != scope.locals.end()) saved = it->second;
  scope.locals[name] = n.a;
  if (set.op == ir::Op::Range) {
    n.count = 0;
    n.kids = {compile(set.children[0], scope), compile(set.children[1], scope)};
  } else if (set.op == ir::Op::EnumSet || set.op == ir::Op::ItemSet) {
    ValueType elem;
    n.count = static_cast<std::uint32_t>(setMembers(set, elem, scope).size());
  } else {
    throw RuntimeError(at(), "a quantifier at run time must range over an enum, an item set or an integer range");
  }
  const bool last = binder + 1 == e.names.size();
  if (last) {
    n.kids.push_back(compile(e.children[1], scope));
    n.kids.push_back(compile(e.children[2], scope));
  } else {
    n.kids.push_back(constNode({1.0}, 1));
    n.kids.push_back(compileQuantifier(e, scope, binder + 1));
  }
  if (saved)
    scope.locals[name] = *saved;
  else
    scope.locals.erase(name);
  return program_.pool_.add(std::move(n));
}

}  // namespace cbtl::rt
