#include "runtime/core/Program.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cbtl::rt {

namespace {

const std::map<std::string, Op>& binaryOps() {
  static const std::map<std::string, Op> ops = {
      {"+", Op::Add},   {"-", Op::Sub}, {"*", Op::Mul},      {"/", Op::Div},  {"%", Op::Mod}, {"^", Op::Pow},
      {"==", Op::Eq},   {"!=", Op::Ne}, {"<", Op::Lt},       {"<=", Op::Le},  {">", Op::Gt},  {">=", Op::Ge},
      {"and", Op::And}, {"or", Op::Or}, {"=>", Op::Implies}, {"<=>", Op::Iff}};
  return ops;
}

}  // namespace

Program::Program(const ir::ConstraintGraph& graph, Builtins builtins) : graph_(graph), builtins_(std::move(builtins)) {
  callContext_ = CallContext{&strings_, builtins_.host().get()};
  strings_.intern("");  // text id 0 is the empty string: the value of an uninitialized text variable
  for (const auto& c : graph_.constants) constants_[c.name] = &c;
  for (const auto& f : graph_.functions) functions_[f.name] = &f;
  layoutVariables();
  layoutObservations();
  compileInitialValues();
  compileConstraints();
  compileDomainChecks();
  compileSamplers();
  compileGenerators();
  itemDescriptors_ = ItemDescriptors(graph_, [this](const ir::Expr& e) { return constantStrings(e); });
  for (const auto& c : graph_.costs) {
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    currentSpan_ = &c.span;
    const std::uint32_t node = compile(c.expr, scope);
    costs_.push_back(c.maximize ? pool_.add(Node{Op::Neg, 1, 0, 0, 0, nullptr, {node}, {}}) : node);
  }
  currentSpan_ = nullptr;
}

// --- expressions --------------------------------------------------------------------------------------

std::uint32_t Program::constNode(std::vector<double> values, std::uint16_t width) {
  values.resize(width, 0.0);
  Node n;
  n.op = Op::Const;
  n.width = width;
  n.a = pool_.addConstants(values);
  return pool_.add(std::move(n));
}

std::vector<double> Program::constantValue(const ir::Expr& e) {
  Scope scope;
  std::uint32_t top = 0;
  scope.frameTop = &top;
  const std::uint32_t node = compile(e, scope);
  std::vector<double> frame(top + 1, 0.0);
  EvalContext ctx{nullptr, nullptr, frame.data(), &callContext_};
  std::vector<double> out(std::max<std::size_t>(pool_.width(node), 1));
  pool_.eval(node, ctx, out.data());
  return out;
}

// A constant item field that is not a literal, as the strings a text-preference model is shown: one per set
// member for a set, otherwise the rendered value.
std::vector<std::string> Program::constantStrings(const ir::Expr& e) {
  const ValueType t = typeOf(e.type);
  std::vector<std::string> out;
  if (t.kind == ValueKind::Set) {
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    ValueType elem;
    for (double m : setMembers(e, elem, scope)) out.push_back(render(elem, &m));
    return out;
  }
  const auto v = constantValue(e);
  out.push_back(render(t, v.data()));
  return out;
}

std::vector<double> Program::setMembers(const ir::Expr& set, ValueType& elem, Scope& scope) {
  std::vector<double> out;
  if (set.op == "enumset") {
    const auto* e = findEnum(set.text);
    elem = ValueType{ValueKind::Enum, 1, set.text};
    for (std::size_t i = 0; e != nullptr && i < e->members.size(); ++i) out.push_back(static_cast<double>(i));
    return out;
  }
  if (set.op == "itemset") {
    const auto* s = findItemSet(set.text);
    elem = ValueType{ValueKind::Item, 1, s != nullptr ? s->itemType : set.text};
    for (std::size_t i = 0; s != nullptr && i < s->entries.size(); ++i) out.push_back(static_cast<double>(i));
    return out;
  }
  if (set.op == "const" && set.children.empty()) {
    auto it = constants_.find(set.text);
    if (it != constants_.end()) return setMembers(it->second->value, elem, scope);
  }
  if (set.op == "list") {
    for (const auto& c : set.children) {
      const auto v = constantValue(c);
      elem = typeOf(c.type);
      out.push_back(v.empty() ? 0 : v[0]);
    }
    return out;
  }
  throw RuntimeError(
      currentSpan_ ? where(*currentSpan_) : "",
      fmt::format("a set given by '{}' is not supported at run time (use an enum, item set or constant list)", set.op));
}

std::uint32_t Program::compileConstRef(const ir::Expr& e, Scope& scope) {
  auto it = constants_.find(e.text);
  if (it == constants_.end())
    throw RuntimeError(currentSpan_ ? where(*currentSpan_) : "", fmt::format("unknown constant '{}'", e.text));
  const ir::Constant& c = *it->second;
  const ValueType t = typeOf(e.type);
  if (e.children.empty()) return constNode(constantValue(c.value), t.width);
  // A constant family indexed at run time: one table entry per member of the index set.
  if (c.value.op != "list")
    throw RuntimeError(where(c.span), fmt::format("constant family '{}' must be a list", c.name));
  std::vector<std::uint32_t> offsets;
  for (const auto& elemExpr : c.value.children) {
    auto v = constantValue(elemExpr);
    v.resize(t.width, 0.0);
    offsets.push_back(pool_.addConstants(v));
  }
  Node n;
  n.op = Op::TableConst;
  n.width = t.width;
  n.count = static_cast<std::uint32_t>(offsets.size());
  n.a = pool_.addTable(offsets);
  n.kids.push_back(compile(e.children[0], scope));
  return pool_.add(std::move(n));
}

std::uint32_t Program::compileCall(const ir::Expr& e, Scope& scope) {
  const std::string at = currentSpan_ ? where(*currentSpan_) : "";
  auto it = functions_.find(e.text);
  const ir::Function* f = it == functions_.end() ? nullptr : it->second;
  std::vector<std::uint32_t> args;
  for (const auto& c : e.children) args.push_back(compile(c, scope));
  if (f != nullptr && !f->isExtern && f->body) {
    // Inline the body with its parameters bound to the argument nodes (bodies are pure expressions).
    if (++inlineDepth_ > 64) throw RuntimeError(at, fmt::format("function '{}' expands too deeply", e.text));
    Scope inner;
    inner.params = args;
    inner.frameTop = scope.frameTop;
    const std::uint32_t node = compile(*f->body, inner);
    --inlineDepth_;
    return node;
  }
  if (f != nullptr && f->kind != "function") {
    throw RuntimeError(at, fmt::format("'{}' is a {} and cannot be called inside an expression", e.text, f->kind));
  }
  FunctionImpl impl = builtins_.function(e.text);
  if (impl == nullptr)
    throw RuntimeError(at, fmt::format("built-in function '{}' has no implementation in this runtime", e.text));
  Node n;
  n.op = Op::Call;
  n.fn = impl;
  n.width = std::max<std::uint16_t>(typeOf(e.type).width, 1);
  n.kids = args;
  std::size_t argsWidth = 0;
  for (std::uint32_t a : args) {
    n.kidWidths.push_back(pool_.width(a));
    argsWidth += pool_.width(a);
  }
  if (argsWidth > kMaxCallArgsWidth) {
    throw RuntimeError(at, fmt::format("the arguments of '{}' take {} doubles, more than the runtime's limit of {}",
                                       e.text, argsWidth, kMaxCallArgsWidth));
  }
  return pool_.add(std::move(n));
}

std::uint32_t Program::compileIn(const ir::Expr& e, Scope& scope) {
  const ir::Expr& set = e.children[1];
  if (set.op == "range") {
    Node n;
    n.op = Op::InRange;
    n.kids = {compile(e.children[0], scope), compile(set.children[0], scope), compile(set.children[1], scope)};
    return pool_.add(std::move(n));
  }
  if (set.op == "obs" && set.children.empty()) {
    // An observed set: its membership flags, indexed by the element's member index.
    auto it = obsSlots_.find(set.text);
    if (it != obsSlots_.end() && it->second.type.kind == ValueKind::Set) {
      std::vector<std::uint32_t> offsets(it->second.type.width);
      for (std::size_t i = 0; i < offsets.size(); ++i) offsets[i] = it->second.offset + static_cast<std::uint32_t>(i);
      Node n;
      n.op = Op::TableObs;
      n.a = pool_.addTable(offsets);
      n.count = static_cast<std::uint32_t>(offsets.size());
      n.kids = {compile(e.children[0], scope)};
      return pool_.add(std::move(n));
    }
  }
  ValueType elem;
  const auto members = setMembers(set, elem, scope);
  Node n;
  n.op = Op::InSet;
  n.a = pool_.addConstants(members);
  n.b = static_cast<std::uint32_t>(members.size());
  n.kids = {compile(e.children[0], scope)};
  return pool_.add(std::move(n));
}

std::uint32_t Program::compileQuantifier(const ir::Expr& e, Scope& scope, std::size_t binder) {
  const ir::Expr& set = e.children[0];
  Node n;
  n.op = e.op == "forall" ? Op::Forall : Op::Exists;
  n.a = (*scope.frameTop)++;
  const std::string name = e.names[binder];
  std::optional<std::uint32_t> saved;
  if (auto it = scope.locals.find(name); it != scope.locals.end()) saved = it->second;
  scope.locals[name] = n.a;
  if (set.op == "range") {
    n.count = 0;
    n.kids = {compile(set.children[0], scope), compile(set.children[1], scope)};
  } else if (set.op == "enumset" || set.op == "itemset") {
    ValueType elem;
    n.count = static_cast<std::uint32_t>(setMembers(set, elem, scope).size());
  } else {
    throw RuntimeError(currentSpan_ ? where(*currentSpan_) : "",
                       "a quantifier at run time must range over an enum, an item set or an integer range");
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
  return pool_.add(std::move(n));
}

std::uint32_t Program::compile(const ir::Expr& e, Scope& scope) {
  const std::uint32_t node = compileExpr(e, scope);
  if (pool_.width(node) > kMaxValueWidth) {
    throw RuntimeError(currentSpan_ ? where(*currentSpan_) : "",
                       fmt::format("a value of {} doubles ('{}' of type {}) is wider than the runtime's limit of {}",
                                   pool_.width(node), e.text.empty() ? e.op : e.text, e.type.spelling, kMaxValueWidth));
  }
  const PackedNode& packed = pool_.node(node);
  if ((packed.op == Op::TableVar || packed.op == Op::TableObs || packed.op == Op::TableConst) && packed.count == 0) {
    throw RuntimeError(currentSpan_ ? where(*currentSpan_) : "", fmt::format("'{}' indexes an empty family", e.text));
  }
  if (scope.frameTop != nullptr) frameSize_ = std::max<std::size_t>(frameSize_, *scope.frameTop);
  return node;
}

std::uint32_t Program::compileExpr(const ir::Expr& e, Scope& scope) {
  const std::string at = currentSpan_ ? where(*currentSpan_) : "";
  const ValueType t = typeOf(e.type);
  const std::string& op = e.op;
  if (op == "num" || op == "bool") return constNode({e.number}, 1);
  if (op == "str") return constNode({static_cast<double>(strings_.intern(e.text))}, 1);
  if (op == "enum" || op == "item") return constNode({memberIndex(e.extra, e.text)}, 1);
  if (op == "var") {
    if (e.id < 0 || static_cast<std::size_t>(e.id) >= slots_.size())
      throw RuntimeError(at, fmt::format("unknown variable '{}'", e.text));
    const VarSlot& s = slots_[static_cast<std::size_t>(e.id)];
    return pool_.add(Node{Op::ReadVar, s.type.width, s.offset, 0, 0, nullptr, {}, {}});
  }
  if (op == "param") {
    if (e.id < 0 || static_cast<std::size_t>(e.id) >= scope.params.size() ||
        scope.params[static_cast<std::size_t>(e.id)] == UINT32_MAX) {
      // A learning rule's labels and condition see only the parameters its event binds.
      throw RuntimeError(
          at,
          fmt::format("parameter '{}' is not bound here (a learning rule must bind every parameter it reads)", e.text));
    }
    return scope.params[static_cast<std::size_t>(e.id)];
  }
  if (op == "local") {
    auto it = scope.locals.find(e.text);
    if (it == scope.locals.end()) throw RuntimeError(at, fmt::format("'{}' is not bound here", e.text));
    return pool_.add(Node{Op::ReadFrame, std::max<std::uint16_t>(t.width, 1), it->second, 0, 0, nullptr, {}, {}});
  }
  if (op == "const") return compileConstRef(e, scope);
  if (op == "obs") {
    if (e.children.empty()) {
      auto slot = obsSlots_.find(e.text);
      if (slot == obsSlots_.end()) throw RuntimeError(at, fmt::format("unknown observation '{}'", e.text));
      return pool_.add(Node{Op::ReadObs, slot->second.type.width, slot->second.offset, 0, 0, nullptr, {}, {}});
    }
    const ir::Observation* decl = nullptr;
    for (const auto& o : graph_.observations) {
      if (o.name == e.text) decl = &o;
    }
    if (decl == nullptr || !decl->indexSet)
      throw RuntimeError(at, fmt::format("'{}' is not an observation family", e.text));
    ValueType elem;
    Scope none;
    std::uint32_t top = 0;
    none.frameTop = &top;
    const auto members = setMembers(*decl->indexSet, elem, none);
    std::vector<std::uint32_t> offsets;
    for (double m : members) {
      const std::string key = e.text + "[" + render(elem, &m) + "]";
      offsets.push_back(obsSlots_.at(key).offset);
    }
    Node n{Op::TableObs, t.width, pool_.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr,
           {},           {}};
    n.kids.push_back(compile(e.children[0], scope));
    return pool_.add(std::move(n));
  }
  if (op == "family") {
    // e.vars holds the members in no particular order: map each to its index by the member's name.
    const ir::Expr& index = e.children[0];
    const ValueType it = typeOf(index.type);
    std::vector<std::pair<double, ir::VarId>> byIndex;
    for (ir::VarId v : e.vars) {
      const auto& var = graph_.variables.at(v);
      double idx = 0;
      if (it.kind == ValueKind::Int)
        idx = std::stod(var.indexText);
      else
        idx = memberIndex(it.typeName, var.indexText);
      byIndex.emplace_back(idx, v);
    }
    std::sort(byIndex.begin(), byIndex.end());
    std::vector<std::uint32_t> offsets;
    double first = byIndex.empty() ? 0 : byIndex.front().first;
    for (std::size_t i = 0; i < byIndex.size(); ++i) {
      if (byIndex[i].first != first + static_cast<double>(i))
        throw RuntimeError(at, fmt::format("family '{}' has gaps in its index", e.text));
      offsets.push_back(slots_[byIndex[i].second].offset);
    }
    std::uint32_t idxNode = compile(index, scope);
    if (first != 0) {
      idxNode = pool_.add(Node{Op::Sub, 1, 0, 0, 0, nullptr, {idxNode, constNode({first}, 1)}, {}});
    }
    Node n{Op::TableVar, t.width, pool_.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr,
           {idxNode},    {}};
    return pool_.add(std::move(n));
  }
  if (op == "member") {
    const ir::Expr& base = e.children[0];
    const ValueType bt = typeOf(base.type);
    const std::uint32_t baseNode = compile(base, scope);
    std::uint32_t offset = 0;
    std::uint16_t width = std::max<std::uint16_t>(t.width, 1);
    if (bt.kind == ValueKind::Item) {
      const auto* items = findItemSetOfType(bt.typeName);
      if (items == nullptr) throw RuntimeError(at, fmt::format("no item set of type '{}'", bt.typeName));
      std::vector<std::uint32_t> offsets;
      for (const auto& entry : items->entries) {
        std::vector<double> v(width, 0.0);
        for (const auto& [field, value] : entry.fields) {
          if (field == e.text) v = constantValue(value);
        }
        v.resize(width, 0.0);
        offsets.push_back(pool_.addConstants(v));
      }
      Node n{Op::TableConst, width, pool_.addTable(offsets), 0, static_cast<std::uint32_t>(offsets.size()), nullptr,
             {baseNode},     {}};
      return pool_.add(std::move(n));
    }
    const std::string& m = e.text;
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
      throw RuntimeError(at, fmt::format("member '{}' of {} is not supported at run time", m, toString(bt.kind)));
    return pool_.add(Node{Op::Member, width, offset, 0, 0, nullptr, {baseNode}, {}});
  }
  if (op == "neg" || op == "not") {
    Node n{op == "neg" ? Op::Neg : Op::Not,
           std::max<std::uint16_t>(t.width, 1),
           0,
           0,
           0,
           nullptr,
           {compile(e.children[0], scope)},
           {}};
    return pool_.add(std::move(n));
  }
  if (op == "+" && t.kind == ValueKind::Text) {
    Node n{Op::Call, 1, 0, 0, 0, concatTexts, {compile(e.children[0], scope), compile(e.children[1], scope)}, {1, 1}};
    return pool_.add(std::move(n));
  }
  if (auto b = binaryOps().find(op); b != binaryOps().end()) {
    Node n;
    n.op = b->second;
    n.width = std::max<std::uint16_t>(t.width, 1);
    n.kids = {compile(e.children[0], scope), compile(e.children[1], scope)};
    if (n.op == Op::Div && e.children[0].type.kind == "int" && e.children[1].type.kind == "int") n.b = 1;
    if (n.op >= Op::Eq) n.width = 1;
    return pool_.add(std::move(n));
  }
  if (op == "in") return compileIn(e, scope);
  if (op == "if") {
    Node n{Op::If, std::max<std::uint16_t>(t.width, 1), 0, 0, 0, nullptr, {}, {}};
    for (const auto& c : e.children) n.kids.push_back(compile(c, scope));
    return pool_.add(std::move(n));
  }
  if (op == "call") return compileCall(e, scope);
  if (op == "forall" || op == "exists") return compileQuantifier(e, scope, 0);
  if (op == "tuple") {
    Node n{Op::Concat, 0, 0, 0, 0, nullptr, {}, {}};
    std::size_t width = 0;
    for (const auto& c : e.children) {
      n.kids.push_back(compile(c, scope));
      width += pool_.width(n.kids.back());
      if (width > kMaxValueWidth) {
        throw RuntimeError(
            at, fmt::format("a tuple of more than {} doubles is wider than the runtime's limit", kMaxValueWidth));
      }
    }
    n.width = static_cast<std::uint16_t>(width);
    return pool_.add(std::move(n));
  }
  throw RuntimeError(at, fmt::format("expression '{}' is not supported at run time", op));
}

// --- constraints, samplers, generators ----------------------------------------------------------------

void Program::compileConstraints() {
  for (const auto& c : graph_.constraints) {
    currentSpan_ = &c.span;
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    constraints_.push_back(CompiledConstraint{&c, compile(c.expr, scope)});
  }
  currentSpan_ = nullptr;
}

void Program::compileDomainChecks() {
  domainChecks_.resize(graph_.variables.size());
  for (const auto& v : graph_.variables) {
    currentSpan_ = &v.span;
    DomainCheck& check = domainChecks_[v.id];
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    for (const auto& b : v.domain.bounds) {
      check.lo.push_back(b.lo ? compile(*b.lo, scope) : UINT32_MAX);
      check.hi.push_back(b.hi ? compile(*b.hi, scope) : UINT32_MAX);
    }
    if (v.domain.set && v.domain.set->op != "obs") {
      ValueType elem;
      check.members = setMembers(*v.domain.set, elem, scope);
    }
  }
  currentSpan_ = nullptr;
}

void Program::compileSamplers() {
  for (const auto& s : graph_.samplers) {
    currentSpan_ = &s.span;
    CompiledSampler cs;
    cs.source = &s;
    cs.writes = s.writes;
    Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    if (s.sampler == "uniform") {
      for (ir::VarId v : s.writes) {
        const auto& var = graph_.variables.at(v);
        const ValueType& t = slots_[v].type;
        UniformPlan plan;
        // An observed set draws from every member of the type; the variable's `.domain` constraint (added by
        // the compiler) rejects the members the observation leaves out.
        if (var.domain.set && var.domain.set->op != "obs") {
          ValueType elem;
          plan.kind = UniformPlan::Kind::Choice;
          plan.choices = setMembers(*var.domain.set, elem, scope);
        } else if (t.kind == ValueKind::Bool) {
          plan.kind = UniformPlan::Kind::Bool;
        } else if (t.kind == ValueKind::Enum || t.kind == ValueKind::Item) {
          plan.kind = UniformPlan::Kind::Choice;
          ir::Expr set;
          set.op = t.kind == ValueKind::Enum ? "enumset" : "itemset";
          set.text = t.kind == ValueKind::Enum
                         ? t.typeName
                         : (findItemSetOfType(t.typeName) ? findItemSetOfType(t.typeName)->name : t.typeName);
          ValueType elem;
          plan.choices = setMembers(set, elem, scope);
        } else if (t.kind == ValueKind::Real || t.kind == ValueKind::Int || t.kind == ValueKind::Vec ||
                   t.kind == ValueKind::SE2 || t.kind == ValueKind::SE3 || t.kind == ValueKind::Conf) {
          plan.kind = t.kind == ValueKind::Int ? UniformPlan::Kind::Int : UniformPlan::Kind::Real;
          if (var.domain.bounds.size() != t.width) {
            throw RuntimeError(where(s.span),
                               fmt::format("'uniform' needs bounds on every component of '{}'", var.name));
          }
          for (const auto& b : var.domain.bounds) {
            if (!b.lo || !b.hi)
              throw RuntimeError(where(s.span), fmt::format("'uniform' needs '{}' to be bounded", var.name));
            plan.lo.push_back(compile(*b.lo, scope));
            plan.hi.push_back(compile(*b.hi, scope));
          }
        } else {
          throw RuntimeError(where(s.span),
                             fmt::format("'uniform' cannot draw '{}' of type {}", var.name, var.type.spelling));
        }
        if (plan.kind == UniformPlan::Kind::Choice && plan.choices.empty()) {
          throw RuntimeError(where(s.span), fmt::format("'{}' has an empty domain", var.name));
        }
        cs.uniform.push_back(std::move(plan));
      }
    } else {
      cs.impl = builtins_.sampler(s.sampler);
      if (cs.impl == nullptr)
        throw RuntimeError(where(s.span),
                           fmt::format("built-in sampler '{}' has no implementation in this runtime", s.sampler));
      for (const auto& a : s.args) {
        cs.args.push_back(compile(a, scope));
        cs.argWidths.push_back(pool_.width(cs.args.back()));
        cs.argsWidth += cs.argWidths.back();
      }
    }
    for (ir::VarId v : cs.writes) cs.outWidth += slots_.at(v).type.width;
    maxSamplerOut_ = std::max(maxSamplerOut_, cs.outWidth);
    maxSamplerArgs_ = std::max(maxSamplerArgs_, cs.argsWidth);
    samplers_.push_back(std::move(cs));
  }
  currentSpan_ = nullptr;
}

void Program::compileGenerators() {
  for (const auto& g : graph_.generators) {
    currentSpan_ = &g.span;
    CompiledGenerator cg;
    cg.source = &g;
    for (const auto& f : g.factors) {
      if (f.kind != "interval" && f.kind != "threshold" && f.kind != "table" && f.kind != "text") {
        throw RuntimeError(where(f.span), fmt::format("model kind '{}' is not supported", f.kind));
      }
      cg.factors.push_back(CompiledFactor{&f});
    }
    for (const auto& r : g.learnRules) {
      currentSpan_ = &r.span;
      CompiledLearnRule cr;
      cr.source = &r;
      bool found = false;
      for (std::size_t i = 0; i < graph_.feedback.size(); ++i) {
        if (graph_.feedback[i].name == r.event) {
          cr.eventIndex = static_cast<std::uint32_t>(i);
          found = true;
        }
      }
      if (!found) throw RuntimeError(where(r.span), fmt::format("unknown feedback event '{}'", r.event));
      const auto& ev = graph_.feedback[cr.eventIndex];
      std::uint32_t top = 0;
      Scope scope;
      scope.frameTop = &top;
      scope.params.assign(g.params.size(), UINT32_MAX);
      for (std::size_t i = 0; i < r.binders.size() && i < ev.params.size(); ++i) {
        const ValueType bt = typeOf(ev.params[i].type);
        cr.binderTypes.push_back(bt);
        cr.binderFrame.push_back(top);
        if (r.binders[i] != "_") scope.locals[r.binders[i]] = top;
        for (std::size_t p = 0; p < g.params.size(); ++p) {
          if (i < r.binds.size() && r.binds[i] == g.params[p].name) {
            scope.params[p] =
                pool_.add(Node{Op::ReadFrame, std::max<std::uint16_t>(bt.width, 1), top, 0, 0, nullptr, {}, {}});
          }
        }
        top += std::max<std::uint16_t>(bt.width, 1);
      }
      for (const auto& l : r.labels) {
        int factor = -1;
        for (std::size_t k = 0; k < g.factors.size(); ++k) {
          if (l.factor.empty() ? g.factors.size() == 1 : g.factors[k].label == l.factor) factor = static_cast<int>(k);
        }
        if (factor < 0) throw RuntimeError(where(r.span), fmt::format("label names no factor of '{}'", g.name));
        const auto& f = g.factors[static_cast<std::size_t>(factor)];
        std::uint32_t featureNode = UINT32_MAX;
        if (f.feature) {
          for (const auto& pn : f.params) {
            for (std::size_t p = 0; p < g.params.size(); ++p) {
              if (g.params[p].name == pn && scope.params[p] == UINT32_MAX) {
                throw RuntimeError(
                    where(r.span),
                    fmt::format("learning rule '{}' does not bind parameter '{}', which factor '{}' reads", r.event, pn,
                                f.label));
              }
            }
          }
          featureNode = compile(*f.feature, scope);
        }
        cr.labels.push_back({factor, compile(l.value, scope)});
        cr.features.push_back(featureNode);
      }
      if (r.condition) cr.condition = compile(*r.condition, scope);
      cr.frameWidth = top;
      frameSize_ = std::max<std::size_t>(frameSize_, top);
      cg.rules.push_back(std::move(cr));
    }
    for (const auto& p : g.params) cg.paramTypes.push_back(typeOf(p.type));
    generators_.push_back(std::move(cg));
  }
  currentSpan_ = nullptr;
}

}  // namespace cbtl::rt
