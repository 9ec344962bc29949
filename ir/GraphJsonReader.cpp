#include "ir/GraphJsonReader.h"

#include "ir/GraphJsonNode.h"

#include "ir/OpNames.h"

#include "ir/GraphPrinter.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <set>

namespace cbtl::ir {
namespace {

using graphjson::child;
using graphjson::fail;
using graphjson::json;
using graphjson::Node;
using graphjson::ReadFailure;

// --- discriminators: each string that selects a meaning is converted in exactly one function -------------

// The enumerator named under `key`, by the one name table (ir/OpNames.h); an unknown name fails with its path.
template <class E>
E knownName(const Node& n, const char* key, std::optional<E> (*fromName)(std::string_view), const char* what) {
  const std::string text = n.text(key);
  if (const std::optional<E> value = fromName(text)) return *value;
  fail(GraphReadOutcome::UnknownName, n.at(key), fmt::format("unknown {} '{}'", what, text));
}

// Operand counts of each expression op (ConstraintGraph.h lists them); -1: any number.
struct OpShape {
  Op op;
  int minChildren, maxChildren;
};
constexpr std::array kOps{
    OpShape{Op::Num, 0, 0},     OpShape{Op::Str, 0, 0},     OpShape{Op::Bool, 0, 0},   OpShape{Op::Var, 0, 0},
    OpShape{Op::Obs, 0, 1},     OpShape{Op::Const, 0, 1},   OpShape{Op::Enum, 0, 0},   OpShape{Op::Item, 0, 0},
    OpShape{Op::EnumSet, 0, 0}, OpShape{Op::ItemSet, 0, 0}, OpShape{Op::Param, 0, 0},  OpShape{Op::Local, 0, 0},
    OpShape{Op::Call, 0, -1},   OpShape{Op::Member, 1, 1},  OpShape{Op::Index, 2, -1}, OpShape{Op::Neg, 1, 1},
    OpShape{Op::Not, 1, 1},     OpShape{Op::Add, 2, 2},     OpShape{Op::Sub, 2, 2},    OpShape{Op::Mul, 2, 2},
    OpShape{Op::Div, 2, 2},     OpShape{Op::Mod, 2, 2},     OpShape{Op::Pow, 2, 2},    OpShape{Op::Eq, 2, 2},
    OpShape{Op::Ne, 2, 2},      OpShape{Op::Lt, 2, 2},      OpShape{Op::Le, 2, 2},     OpShape{Op::Gt, 2, 2},
    OpShape{Op::Ge, 2, 2},      OpShape{Op::And, 2, 2},     OpShape{Op::Or, 2, 2},     OpShape{Op::Implies, 2, 2},
    OpShape{Op::Iff, 2, 2},     OpShape{Op::Range, 2, 2},   OpShape{Op::In, 2, 2},     OpShape{Op::Forall, 3, 3},
    OpShape{Op::Exists, 3, 3},  OpShape{Op::If, 3, 3},      OpShape{Op::Tuple, 0, -1}, OpShape{Op::List, 0, -1},
    OpShape{Op::Family, 1, 1},
};

const OpShape& readOp(const Node& n) {
  const Op op = knownName(n, "op", opFromName, "operation");
  for (const auto& shape : kOps) {
    if (shape.op == op) return shape;
  }
  fail(GraphReadOutcome::UnknownName, n.at("op"), fmt::format("operation '{}' cannot be read", name(op)));
}

TypeKind readTypeKind(const Node& n, const char* key) { return knownName(n, key, typeKindFromName, "type kind"); }

// A type: its spelling under `key`, its kind under `kindKey`.
TypeDesc readType(const Node& n, const char* key, const char* kindKey) {
  TypeDesc t;
  t.kind = readTypeKind(n, kindKey);
  t.spelling = n.text(key);
  return t;
}

PatternKind readPatternKind(const Node& n) { return knownName(n, "kind", patternKindFromName, "pattern kind"); }
FactorKind readFactorKind(const Node& n) { return knownName(n, "kind", factorKindFromName, "model factor kind"); }
ThresholdDirection readDirection(const Node& n) {
  return knownName(n, "direction", thresholdDirectionFromName, "threshold direction");
}
TextScale readScale(const Node& n) { return knownName(n, "scale", textScaleFromName, "text scale"); }
TextRating readRating(const Node& n) { return knownName(n, "rating", textRatingFromName, "text rating"); }
ActionKind readActionKind(const Node& n) { return knownName(n, "kind", actionKindFromName, "action kind"); }
AllowPart readAllowPart(const Node& n) { return knownName(n, "part", allowPartFromName, "allow part"); }
FunctionKind readFunctionKind(const Node& n) { return knownName(n, "kind", functionKindFromName, "function kind"); }

// --- the graph ------------------------------------------------------------------------------------------

constexpr int kMaxExprDepth = 1000;  // deeper nesting is no compiler's output; it would only exhaust the stack

class GraphReader {
 public:
  explicit GraphReader(const Node& root) : root_(root) {
    variableCount_ = root.array("variables").size();
    constraintCount_ = root.array("constraints").size();
    samplerCount_ = root.array("samplers").size();
    costCount_ = root.array("costs").size();
  }

  ConstraintGraph read() {
    ConstraintGraph g;
    g.domain = root_.text("domain");
    g.world = root_.text("world");
    if (root_.has("simulator")) {
      const Node s = root_.object("simulator");
      g.simulator = s.text("command");
      g.simulatorSpan = span(s);
    }
    each("clearances", [&](const Node& n) {
      g.clearances.push_back(clearance(n));
      clearanceNames_.insert(g.clearances.back().name);
    });
    each("robots", [&](const Node& n) {
      g.robots.push_back({n.text("name"), static_cast<int>(n.integer("dof", 0, 1000))});
    });
    each("enums", [&](const Node& n) { g.enums.push_back({n.text("name"), n.texts("members"), span(n)}); });
    each("item_types", [&](const Node& n) { g.itemTypes.push_back(itemType(n)); });
    each("item_sets", [&](const Node& n) { g.itemSets.push_back(itemSet(n)); });
    each("constants", [&](const Node& n) {
      g.constants.push_back(
          {n.text("name"), readType(n, "type", "type_kind"), n.text("index_set"), expr(n.object("value")), span(n)});
    });
    each("observations", [&](const Node& n) {
      g.observations.push_back({n.text("name"), readType(n, "type", "type_kind"), optExpr(n, "index_set"), span(n)});
    });
    each("feedback", [&](const Node& n) { g.feedback.push_back(function(n)); });
    each("functions", [&](const Node& n) { g.functions.push_back(function(n)); });
    each("variables", [&](const Node& n) { g.variables.push_back(variable(n, g.variables.size())); });
    each("constraints", [&](const Node& n) { g.constraints.push_back(constraint(n, g.constraints.size())); });
    each("samplers", [&](const Node& n) { g.samplers.push_back(sampler(n, g.samplers.size())); });
    each("costs", [&](const Node& n) {
      g.costs.push_back({n.boolean("maximize"), expr(n.object("expr")), varIds(n, "vars"), span(n)});
    });
    each("generators", [&](const Node& n) { g.generators.push_back(generator(n)); });
    g.skills = root_.texts("skills");
    each("tasks", [&](const Node& n) { g.tasks.push_back(task(n)); });
    return g;
  }

 private:
  template <class F>
  static void eachIn(const Node& n, const char* key, F&& f) {
    const json& a = n.array(key);
    for (std::size_t i = 0; i < a.size(); ++i) f(Node(a[i], child(n.at(key), i)));
  }
  template <class F>
  void each(const char* key, F&& f) const {
    eachIn(root_, key, f);
  }

  std::vector<VarId> varIds(const Node& n, const char* key) const { return n.indices(key, variableCount_, "variable"); }

  static Span span(const Node& owner) {
    const Node n = owner.object("span");
    return {n.text("file"), n.u32("line"), n.u32("column"), n.u32("end_line"), n.u32("end_column")};
  }

  Expr expr(const Node& n, int depth = 0) const {
    if (depth > kMaxExprDepth)
      fail(GraphReadOutcome::Inconsistent, n.path(), fmt::format("expressions nest deeper than {}", kMaxExprDepth));
    Expr e;
    const OpShape& shape = readOp(n);
    e.op = shape.op;
    e.type = readType(n, "type", "type_kind");
    if (e.op == Op::Num || e.op == Op::Bool) e.number = n.number("value");
    e.text = n.optText("text");
    e.extra = n.optText("extra");
    if (n.has("id")) e.id = n.integer("id", 0, std::numeric_limits<std::int64_t>::max());
    e.names = n.optTexts("names");
    if (n.has("vars")) e.vars = varIds(n, "vars");
    if (n.has("children")) eachIn(n, "children", [&](const Node& c) { e.children.push_back(expr(c, depth + 1)); });
    const auto count = static_cast<int>(e.children.size());
    if (count < shape.minChildren || (shape.maxChildren >= 0 && count > shape.maxChildren)) {
      const std::string wanted = shape.maxChildren < 0 ? fmt::format("at least {}", shape.minChildren)
                                 : shape.minChildren == shape.maxChildren
                                     ? fmt::format("{}", shape.minChildren)
                                     : fmt::format("{} to {}", shape.minChildren, shape.maxChildren);
      fail(GraphReadOutcome::Inconsistent, n.at("children"),
           fmt::format("'{}' takes {} operands, not {}", name(e.op), wanted, count));
    }
    if (e.op == Op::Var) {
      if (!n.has("id")) fail(GraphReadOutcome::MissingField, n.at("id"), "missing field");
      if (static_cast<std::uint64_t>(e.id) >= variableCount_) {
        fail(GraphReadOutcome::OutOfRange, n.at("id"),
             fmt::format("variable {} does not exist (the graph has {})", e.id, variableCount_));
      }
    }
    return e;
  }

  std::optional<Expr> optExpr(const Node& n, const char* key) const {
    const json& j = n.field(key);
    if (j.is_null()) return std::nullopt;
    return expr(Node(j, n.at(key)));
  }

  std::vector<Expr> exprs(const Node& n, const char* key) const {
    std::vector<Expr> out;
    eachIn(n, key, [&](const Node& e) { out.push_back(expr(e)); });
    return out;
  }

  std::vector<Param> params(const Node& n) const {
    std::vector<Param> out;
    eachIn(n, "params", [&](const Node& p) { out.push_back({p.text("name"), readType(p, "type", "type_kind")}); });
    return out;
  }

  ItemType itemType(const Node& n) const {
    ItemType t{n.text("name"), {}, span(n)};
    eachIn(n, "fields", [&](const Node& f) { t.fields.push_back({f.text("name"), readType(f, "type", "type_kind")}); });
    return t;
  }

  ItemSet itemSet(const Node& n) const {
    ItemSet s{n.text("name"), n.text("item_type"), {}, span(n)};
    eachIn(n, "entries", [&](const Node& entry) {
      ItemEntry e{entry.text("name"), {}};
      const Node fields = entry.object("fields");
      const std::vector<std::string> order = entry.texts("field_order");
      for (std::size_t i = 0; i < order.size(); ++i) {
        if (!fields.has(order[i].c_str())) {
          fail(GraphReadOutcome::Inconsistent, child(entry.at("field_order"), i),
               fmt::format("field '{}' is not among the entry's fields", order[i]));
        }
        e.fields.emplace_back(order[i], expr(fields.object(order[i].c_str())));
      }
      if (fields.size() != order.size()) {
        fail(GraphReadOutcome::Inconsistent, entry.at("field_order"),
             fmt::format("lists {} fields, the entry has {}", order.size(), fields.size()));
      }
      s.entries.push_back(std::move(e));
    });
    return s;
  }

  Function function(const Node& n) const {
    Function f;
    f.name = n.text("name");
    f.kind = readFunctionKind(n);
    f.isExtern = n.boolean("extern");
    f.typeParams = n.texts("type_params");
    f.params = params(n);
    f.result = readType(n, "result", "result_kind");
    if (n.has("body")) f.body = expr(n.object("body"));
    f.span = span(n);
    return f;
  }

  static void checkId(const Node& n, std::uint32_t id, std::size_t position) {
    if (id != position) {
      fail(GraphReadOutcome::Inconsistent, n.at("id"),
           fmt::format("id {} at position {} (ids are positions)", id, position));
    }
  }

  Variable variable(const Node& n, std::size_t position) const {
    Variable v;
    v.id = n.u32("id");
    checkId(n, v.id, position);
    v.name = n.text("name");
    v.type = readType(n, "type", "kind");
    eachIn(n, "bounds", [&](const Node& b) { v.domain.bounds.push_back({optExpr(b, "lo"), optExpr(b, "hi")}); });
    v.domain.set = optExpr(n, "set");
    v.init = optExpr(n, "init");
    v.family = n.text("family");
    v.indexText = n.text("index");
    v.scope = n.text("scope");
    v.span = span(n);
    return v;
  }

  Constraint constraint(const Node& n, std::size_t position) const {
    Constraint c;
    c.id = n.u32("id");
    checkId(n, c.id, position);
    c.name = n.text("name");
    c.vars = varIds(n, "vars");
    c.expr = expr(n.object("expr"));
    c.scope = n.text("scope");
    c.span = span(n);
    return c;
  }

  Sampler sampler(const Node& n, std::size_t position) const {
    Sampler s;
    s.id = n.u32("id");
    checkId(n, s.id, position);
    s.sampler = n.text("sampler");
    s.writes = varIds(n, "writes");
    s.reads = varIds(n, "reads");
    s.args = exprs(n, "args");
    s.scope = n.text("scope");
    s.span = span(n);
    return s;
  }

  ModelFactor factor(const Node& n) const {
    ModelFactor f;
    f.label = n.text("label");
    f.kind = readFactorKind(n);
    f.feature = optExpr(n, "feature");
    f.lo = n.number("lo");
    f.hi = n.number("hi");
    f.direction = readDirection(n);
    f.prompt = n.text("prompt");
    f.learning = n.text("learning");
    f.scale = readScale(n);
    f.rating = readRating(n);
    // Optional: graphs emitted before text models took a context have none.
    if (n.has("context")) {
      eachIn(n, "context", [&](const Node& c) {
        f.context.push_back({c.text("name"), expr(c.object("value")), c.texts("params")});
      });
    }
    f.params = n.texts("params");
    f.span = span(n);
    return f;
  }

  LearnRule learnRule(const Node& n) const {
    LearnRule r;
    r.event = n.text("event");
    r.binders = n.texts("binders");
    r.binds = n.texts("binds");
    if (r.binds.size() != r.binders.size()) {
      fail(GraphReadOutcome::Inconsistent, n.at("binds"),
           fmt::format("{} entries for {} binders (one per binder)", r.binds.size(), r.binders.size()));
    }
    eachIn(n, "labels", [&](const Node& l) { r.labels.push_back({l.text("factor"), expr(l.object("value"))}); });
    r.condition = optExpr(n, "condition");
    r.span = span(n);
    return r;
  }

  Generator generator(const Node& n) const {
    Generator g;
    g.name = n.text("name");
    g.params = params(n);
    if (n.integer("arity", 0, std::numeric_limits<std::int64_t>::max()) != static_cast<std::int64_t>(g.params.size())) {
      fail(GraphReadOutcome::Inconsistent, n.at("arity"),
           fmt::format("the generator has {} parameters", g.params.size()));
    }
    eachIn(n, "patterns", [&](const Node& p) {
      Pattern pattern{p.text("param"), p.u32("param_index"), readPatternKind(p), p.text("text"), span(p)};
      if (pattern.paramIndex >= g.params.size()) {
        fail(GraphReadOutcome::OutOfRange, p.at("param_index"),
             fmt::format("parameter {} does not exist (the generator has {})", pattern.paramIndex, g.params.size()));
      }
      g.patterns.push_back(std::move(pattern));
    });
    g.captures = n.texts("captures");
    for (const auto& name : n.texts("per")) g.perKeys.push_back({name, std::nullopt, {}});
    // Optional: graphs written before expression keys have names only.
    if (n.has("per_exprs")) {
      const json& a = n.array("per_exprs");
      if (a.size() != g.perKeys.size()) {
        fail(GraphReadOutcome::Inconsistent, n.at("per_exprs"),
             fmt::format("{} entries for {} keys (one per key)", a.size(), g.perKeys.size()));
      }
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].is_null()) continue;
        const Node k(a[i], child(n.at("per_exprs"), i));
        g.perKeys[i].expr = expr(k.object("expr"));
        g.perKeys[i].params = k.texts("params");
        for (const auto& pn : g.perKeys[i].params) {
          if (std::none_of(g.params.begin(), g.params.end(), [&](const Param& p) { return p.name == pn; }))
            fail(GraphReadOutcome::UnknownName, k.at("params"), fmt::format("'{}' is no parameter", pn));
        }
      }
    }
    eachIn(n, "factors", [&](const Node& f) { g.factors.push_back(factor(f)); });
    g.guard = optExpr(n, "guard");
    g.accept = n.number("accept");
    g.fallback = n.number("fallback");
    // Optional: graphs written before the clause existed explore anywhere.
    const std::string explore = n.optText("explore");
    if (explore != "" && explore != "anywhere" && explore != "accepted") {
      fail(GraphReadOutcome::UnknownName, n.at("explore"), fmt::format("unknown exploration mode '{}'", explore));
    }
    g.exploreAccepted = explore == "accepted";
    eachIn(n, "learn", [&](const Node& r) { g.learnRules.push_back(learnRule(r)); });
    g.span = span(n);
    return g;
  }

  static Clearance clearance(const Node& n) {
    Clearance c{n.text("name"), n.texts("bodies"), n.number("distance"), span(n)};
    if (!(c.distance >= 0)) fail(GraphReadOutcome::Inconsistent, n.at("distance"), "a distance is at least 0");
    if (c.bodies.empty()) fail(GraphReadOutcome::Inconsistent, n.at("bodies"), "a clearance names at least one body");
    return c;
  }

  // Exactly one of "clearance" (a declared clearance's name) and "target" (a text expression).
  Allowance allowance(const Node& n) const {
    Allowance a;
    a.part = readAllowPart(n);
    a.separation = n.number("separation");
    if (n.has("clearance") == n.has("target")) {
      fail(GraphReadOutcome::Inconsistent, n.path(), "an allowance has either a \"clearance\" or a \"target\"");
    }
    if (n.has("clearance")) {
      a.clearance = n.text("clearance");
      if (!clearanceNames_.count(a.clearance)) {
        fail(GraphReadOutcome::OutOfRange, n.at("clearance"),
             fmt::format("clearance '{}' is not declared (not in /clearances)", a.clearance));
      }
    }
    if (n.has("target")) a.target = expr(n.object("target"));
    return a;
  }

  Action action(const Node& n, int depth = 0) const {
    if (depth > kMaxExprDepth)
      fail(GraphReadOutcome::Inconsistent, n.path(), fmt::format("actions nest deeper than {}", kMaxExprDepth));
    Action a;
    a.kind = readActionKind(n);
    a.name = n.optText("name");
    if (n.has("args")) a.args = exprs(n, "args");
    a.binders = n.optTexts("binders");
    if (n.has("set")) a.set = expr(n.object("set"));
    if (n.has("condition")) a.condition = expr(n.object("condition"));
    if (n.has("allow")) a.allow = allowance(n.object("allow"));
    if (n.has("body")) eachIn(n, "body", [&](const Node& b) { a.body.push_back(action(b, depth + 1)); });
    if (n.has("else")) eachIn(n, "else", [&](const Node& b) { a.elseBody.push_back(action(b, depth + 1)); });
    if (a.kind == ActionKind::For && !a.set)
      fail(GraphReadOutcome::MissingField, n.at("set"), "a 'for' action needs its set");
    if (a.kind == ActionKind::If && !a.condition)
      fail(GraphReadOutcome::MissingField, n.at("condition"), "an 'if' action needs its condition");
    if (a.kind == ActionKind::Allow && !a.allow)
      fail(GraphReadOutcome::MissingField, n.at("allow"), "an 'allow' action needs its allowance");
    if (a.kind != ActionKind::Allow && a.allow)
      fail(GraphReadOutcome::Inconsistent, n.at("allow"), "only an 'allow' action has an allowance");
    a.span = span(n);
    return a;
  }

  Task task(const Node& n) const {
    Task t;
    t.name = n.text("name");
    t.implicit = n.boolean("implicit");
    t.vars = varIds(n, "vars");
    t.constraints = n.indices("constraints", constraintCount_, "constraint");
    t.samplers = n.indices("samplers", samplerCount_, "sampler");
    t.costs = n.indices("costs", costCount_, "cost");
    eachIn(n, "instances", [&](const Node& i) {
      SkillInstance si;
      si.skill = i.text("skill");
      si.name = i.text("name");
      si.vars = varIds(i, "vars");
      si.params = varIds(i, "params");
      si.constraints = i.indices("constraints", constraintCount_, "constraint");
      si.samplers = i.indices("samplers", samplerCount_, "sampler");
      eachIn(i, "actions", [&](const Node& a) { si.actions.push_back(action(a)); });
      si.span = span(i);
      t.instances.push_back(std::move(si));
    });
    t.span = span(n);
    return t;
  }

  const Node& root_;
  std::set<std::string> clearanceNames_;  // of /clearances, read before the tasks that name them
  std::size_t variableCount_ = 0, constraintCount_ = 0, samplerCount_ = 0, costCount_ = 0;
};

void checkHeader(const Node& root) {
  if (!root.has("format")) fail(GraphReadOutcome::WrongFormat, "", "not a constraint graph (no \"format\" tag)");
  const json& format = root.field("format");
  if (!format.is_string() || format.get<std::string>() != kGraphJsonFormat) {
    fail(GraphReadOutcome::WrongFormat, root.at("format"),
         fmt::format("expected \"{}\", found {}", kGraphJsonFormat, format.dump()));
  }
  const json& version = root.field("version");
  if (!version.is_number_integer() || version.get<std::int64_t>() != kGraphJsonVersion) {
    fail(GraphReadOutcome::WrongVersion, root.at("version"),
         fmt::format("version {} is not supported (this reader reads version {}; emit the graph again with cbtlc)",
                     version.dump(), kGraphJsonVersion));
  }
}

}  // namespace

const char* toString(GraphReadOutcome outcome) {
  switch (outcome) {
    case GraphReadOutcome::Ok:
      return "ok";
    case GraphReadOutcome::NotJson:
      return "not JSON";
    case GraphReadOutcome::WrongFormat:
      return "wrong format";
    case GraphReadOutcome::WrongVersion:
      return "wrong version";
    case GraphReadOutcome::MissingField:
      return "missing field";
    case GraphReadOutcome::WrongType:
      return "wrong type";
    case GraphReadOutcome::UnknownName:
      return "unknown name";
    case GraphReadOutcome::OutOfRange:
      return "out of range";
    case GraphReadOutcome::Inconsistent:
      return "inconsistent";
  }
  return "?";
}

std::string GraphReadResult::describe(const std::string& file) const {
  if (ok()) return "";
  if (pointer.empty()) return fmt::format("{}: {}", file, message);
  return fmt::format("{}: {}: {}", file, pointer, message);
}

GraphReadResult readGraphJson(std::string_view text) {
  GraphReadResult result;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    result.outcome = GraphReadOutcome::NotJson;
    result.message = fmt::format("not valid JSON (at byte {})", e.byte);
    return result;
  }
  try {
    if (!doc.is_object()) fail(GraphReadOutcome::WrongFormat, "", "expected a constraint graph object");
    const Node root(doc, "");
    checkHeader(root);
    result.graph = GraphReader(root).read();
  } catch (const ReadFailure& f) {
    result = GraphReadResult{};
    result.outcome = f.outcome;
    result.pointer = f.pointer;
    result.message = f.message;
  } catch (const std::exception& e) {
    // Only resource exhaustion can land here; still a result, never an escaping exception.
    result = GraphReadResult{};
    result.outcome = GraphReadOutcome::Inconsistent;
    result.message = fmt::format("cannot read the graph: {}", e.what());
  }
  return result;
}

bool looksLikeGraphJson(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    return c == '{';
  }
  return false;
}

}  // namespace cbtl::ir
