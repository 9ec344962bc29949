#include "ir/GraphPrinter.h"

#include "ir/Counted.h"

#include "ir/OpNames.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <sstream>

namespace cbtl::ir {
namespace {

using nlohmann::json;

std::string num(double v) {
  std::string s = fmt::format("{}", v);
  return s;
}

std::string spanText(const Span& s) { return fmt::format("{}:{}:{}", s.file, s.line, s.column); }

json spanJson(const Span& s) {
  return json{
      {"file", s.file}, {"line", s.line}, {"column", s.column}, {"end_line", s.endLine}, {"end_column", s.endColumn}};
}

json exprJson(const Expr& e) {
  json j{{"op", name(e.op)}, {"type", e.type.spelling}, {"type_kind", name(e.type.kind)}};
  if (e.op == Op::Num || e.op == Op::Bool) j["value"] = e.number;
  if (!e.text.empty()) j["text"] = e.text;
  if (!e.extra.empty()) j["extra"] = e.extra;
  if (e.id >= 0) j["id"] = e.id;
  if (!e.names.empty()) j["names"] = e.names;
  if (!e.vars.empty()) j["vars"] = e.vars;
  if (!e.children.empty()) {
    json c = json::array();
    for (const auto& ch : e.children) c.push_back(exprJson(ch));
    j["children"] = std::move(c);
  }
  return j;
}

json optExpr(const std::optional<Expr>& e) { return e ? exprJson(*e) : json(nullptr); }

json allowanceJson(const Allowance& a) {
  json j{{"part", name(a.part)}, {"separation", a.separation}};
  if (a.target)
    j["target"] = exprJson(*a.target);
  else
    j["clearance"] = a.clearance;
  return j;
}

json actionJson(const Action& a) {
  json j{{"kind", name(a.kind)}, {"span", spanJson(a.span)}};
  if (a.allow) j["allow"] = allowanceJson(*a.allow);
  if (!a.name.empty()) j["name"] = a.name;
  if (!a.args.empty()) {
    json args = json::array();
    for (const auto& x : a.args) args.push_back(exprJson(x));
    j["args"] = std::move(args);
  }
  if (!a.binders.empty()) j["binders"] = a.binders;
  if (a.set) j["set"] = exprJson(*a.set);
  if (a.condition) j["condition"] = exprJson(*a.condition);
  if (!a.body.empty()) {
    json b = json::array();
    for (const auto& x : a.body) b.push_back(actionJson(x));
    j["body"] = std::move(b);
  }
  if (!a.elseBody.empty()) {
    json b = json::array();
    for (const auto& x : a.elseBody) b.push_back(actionJson(x));
    j["else"] = std::move(b);
  }
  return j;
}

// The spelling of an operator written between its two operands, or empty.
std::string_view infix(Op op) {
  if (isBinary(op) || op == Op::In) return name(op);
  if (op == Op::Range) return "..";
  return {};
}

std::string varName(VarId id, const ConstraintGraph& g) {
  return id < g.variables.size() ? g.variables[id].name : fmt::format("<var {}>", id);
}

// `allow held near clearance person 0.005 m`, `allow gripper touch "table" 0.01 m`: the separation as a mode and a
// distance, in metres.
std::string allowanceText(const Allowance& a, const ConstraintGraph& g) {
  const std::string target = a.target ? exprText(*a.target, g) : "clearance " + a.clearance;
  return fmt::format("allow {} {} {} {} m", name(a.part), a.separation < 0 ? "touch" : "near", target,
                     num(a.separation < 0 ? -a.separation : a.separation));
}

// The allow blocks of an action tree, one line each, indented by their nesting, with the actions they cover.
void allowLines(const Action& a, const ConstraintGraph& g, int depth, std::ostringstream& o) {
  int inner = depth;
  if (a.kind == ActionKind::Allow && a.allow) {
    o << std::string(static_cast<std::size_t>(2 * depth), ' ') << allowanceText(*a.allow, g) << " ("
      << counted(a.body.size(), "action") << ")  @" << spanText(a.span) << "\n";
    ++inner;
  }
  for (const auto& b : a.body) allowLines(b, g, inner, o);
  for (const auto& b : a.elseBody) allowLines(b, g, inner, o);
}

std::string clearanceText(const Clearance& c) {
  std::string bodies;
  for (std::size_t i = 0; i < c.bodies.size(); ++i) bodies += (i ? ", " : "") + nlohmann::json(c.bodies[i]).dump();
  return fmt::format("clearance {}: {} >= {} m", c.name, bodies, num(c.distance));
}

}  // namespace

std::string exprText(const Expr& e, const ConstraintGraph& g) {
  auto kids = [&](const char* sep) {
    std::string s;
    for (std::size_t i = 0; i < e.children.size(); ++i) s += (i ? sep : "") + exprText(e.children[i], g);
    return s;
  };
  switch (e.op) {
    case Op::Num:
      return e.text.empty() ? num(e.number) : e.text;
    case Op::Str:
      return nlohmann::json(e.text).dump();
    case Op::Bool:
      return e.number != 0 ? "true" : "false";
    case Op::Var:
      return varName(static_cast<VarId>(e.id), g);
    case Op::Enum:
    case Op::Item:
      return e.extra + "." + e.text;
    case Op::Param:
      return fmt::format("${}", e.text);
    case Op::Local:
    case Op::EnumSet:
    case Op::ItemSet:
      return e.text;
    case Op::Const:
    case Op::Obs:
    case Op::Family:
      return e.children.empty() ? e.text : fmt::format("{}[{}]", e.text, kids(", "));
    case Op::Call:
      return fmt::format("{}({})", e.text, kids(", "));
    case Op::Member:
      return fmt::format("{}.{}", exprText(e.children[0], g), e.text);
    case Op::Index: {
      std::string s = exprText(e.children[0], g) + "[";
      for (std::size_t i = 1; i < e.children.size(); ++i) s += (i > 1 ? ", " : "") + exprText(e.children[i], g);
      return s + "]";
    }
    case Op::Neg:
      return "-" + exprText(e.children[0], g);
    case Op::Not:
      return "not " + exprText(e.children[0], g);
    case Op::Forall:
    case Op::Exists: {
      std::string names;
      for (std::size_t i = 0; i < e.names.size(); ++i) names += (i ? ", " : "") + e.names[i];
      std::string where =
          e.children[1].op == Op::Bool && e.children[1].number != 0 ? "" : " where " + exprText(e.children[1], g);
      return fmt::format("({} {} in {}{}: {})", name(e.op), names, exprText(e.children[0], g), where,
                         exprText(e.children[2], g));
    }
    case Op::If:
      return fmt::format("(if {} then {} else {})", exprText(e.children[0], g), exprText(e.children[1], g),
                         exprText(e.children[2], g));
    case Op::Tuple:
      return "(" + kids(", ") + ")";
    case Op::List:
      return "[" + kids(", ") + "]";
    default:
      break;
  }
  if (const std::string_view op = infix(e.op); !op.empty() && e.children.size() == 2) {
    return fmt::format("({} {} {})", exprText(e.children[0], g), op, exprText(e.children[1], g));
  }
  return fmt::format("<{}>", name(e.op));
}

std::string toText(const ConstraintGraph& g) {
  std::ostringstream o;
  o << "domain " << (g.domain.empty() ? "<unnamed>" : g.domain) << "\n";
  if (!g.world.empty()) o << "world " << nlohmann::json(g.world).dump() << "\n";
  if (!g.simulator.empty()) o << "simulator " << nlohmann::json(g.simulator).dump() << "\n";
  o << fmt::format("summary: {}, {}, {}, {}, {}\n", counted(g.tasks.size(), "task"),
                   counted(g.variables.size(), "variable"), counted(g.constraints.size(), "constraint"),
                   counted(g.samplers.size(), "sampler"), counted(g.generators.size(), "generator"));
  for (const auto& c : g.clearances) o << clearanceText(c) << "  @" << spanText(c.span) << "\n";
  for (const auto& v : g.variables) {
    o << fmt::format("var %{} {} : {}", v.id, v.name, v.type.spelling);
    if (!v.domain.bounds.empty()) {
      o << " in [";
      for (std::size_t i = 0; i < v.domain.bounds.size(); ++i) {
        const auto& b = v.domain.bounds[i];
        o << (i ? ", " : "") << (b.lo ? exprText(*b.lo, g) : "-inf") << " .. " << (b.hi ? exprText(*b.hi, g) : "inf");
      }
      o << "]";
    }
    if (v.domain.set) o << " in " << exprText(*v.domain.set, g);
    if (v.init) o << " = " << exprText(*v.init, g);
    o << "  (" << v.scope << ")\n";
  }
  for (const auto& c : g.constraints) {
    o << fmt::format("constraint #{} {} over {{", c.id, c.name);
    for (std::size_t i = 0; i < c.vars.size(); ++i) o << (i ? ", " : "") << varName(c.vars[i], g);
    o << "}: " << exprText(c.expr, g) << "  @" << spanText(c.span) << "\n";
  }
  for (const auto& s : g.samplers) {
    o << fmt::format("sampler #{} {}", s.id, s.sampler);
    if (!s.args.empty()) {
      o << "(";
      for (std::size_t i = 0; i < s.args.size(); ++i) o << (i ? ", " : "") << exprText(s.args[i], g);
      o << ")";
    }
    o << " writes {";
    for (std::size_t i = 0; i < s.writes.size(); ++i) o << (i ? ", " : "") << varName(s.writes[i], g);
    o << "} reads {";
    for (std::size_t i = 0; i < s.reads.size(); ++i) o << (i ? ", " : "") << varName(s.reads[i], g);
    o << "}\n";
  }
  for (std::size_t i = 0; i < g.costs.size(); ++i) {
    o << fmt::format("cost #{} {} {}\n", i, g.costs[i].maximize ? "maximize" : "minimize",
                     exprText(g.costs[i].expr, g));
  }
  for (const auto& gen : g.generators) {
    o << "generator " << gen.name << " arity " << gen.params.size() << " (";
    for (std::size_t i = 0; i < gen.params.size(); ++i)
      o << (i ? ", " : "") << gen.params[i].name << ": " << gen.params[i].type.spelling;
    o << ")\n";
    for (const auto& p : gen.patterns)
      o << fmt::format("  when {} ~ {} {}\n", p.param, name(p.kind), nlohmann::json(p.text).dump());
    for (const auto& f : gen.factors) {
      o << "  model " << f.label << " = " << name(f.kind);
      if (f.feature) o << "(" << exprText(*f.feature, g);
      if (f.kind == FactorKind::Interval || f.kind == FactorKind::Threshold)
        o << ", " << num(f.lo) << " .. " << num(f.hi);
      if (f.direction != ThresholdDirection::None) o << ", " << name(f.direction);
      if (f.kind == FactorKind::Text) {
        if (!f.prompt.empty()) o << ", prompt " << nlohmann::json(f.prompt).dump();
        if (!f.learning.empty()) o << ", learning " << nlohmann::json(f.learning).dump();
        o << ", scale " << name(f.scale) << ", rating " << name(f.rating);
        if (!f.context.empty()) {
          o << ", context [";
          for (std::size_t i = 0; i < f.context.size(); ++i) o << (i ? ", " : "") << exprText(f.context[i].value, g);
          o << "]";
        }
      }
      o << ")\n";
    }
    if (!gen.perKeys.empty()) {
      o << "  per";
      for (std::size_t i = 0; i < gen.perKeys.size(); ++i) {
        const auto& k = gen.perKeys[i];
        o << (i ? ", " : " ") << (k.expr ? exprText(*k.expr, g) : k.name);
      }
      o << "\n";
    }
    if (gen.guard) o << "  if " << exprText(*gen.guard, g) << "\n";
    o << "  accept " << num(gen.accept) << ", fallback " << num(gen.fallback)
      << (gen.exploreAccepted ? ", explore accepted" : "") << "\n";
    for (const auto& r : gen.learnRules) {
      o << "  learn " << r.event << "(";
      for (std::size_t i = 0; i < r.binders.size(); ++i) o << (i ? ", " : "") << r.binders[i];
      o << ") =>";
      for (std::size_t i = 0; i < r.labels.size(); ++i) {
        o << (i ? "," : "") << " " << (r.labels[i].factor.empty() ? "" : r.labels[i].factor + ": ")
          << exprText(r.labels[i].value, g);
      }
      if (r.condition) o << " if " << exprText(*r.condition, g);
      o << "\n";
    }
  }
  for (const auto& t : g.tasks) {
    o << fmt::format("task {}{}: {} variables, {} constraints, {} samplers\n", t.name, t.implicit ? " (implicit)" : "",
                     t.vars.size(), t.constraints.size(), t.samplers.size());
    for (const auto& si : t.instances) {
      o << fmt::format("  run {} as {}: {} variables, {} constraints, {} actions\n", si.skill, si.name, si.vars.size(),
                       si.constraints.size(), si.actions.size());
      for (const auto& a : si.actions) allowLines(a, g, 2, o);
    }
  }
  return o.str();
}

std::string toJson(const ConstraintGraph& g) {
  json j;
  j["format"] = kGraphJsonFormat;
  j["version"] = kGraphJsonVersion;
  j["domain"] = g.domain;
  j["world"] = g.world;
  if (!g.simulator.empty()) j["simulator"] = {{"command", g.simulator}, {"span", spanJson(g.simulatorSpan)}};
  j["clearances"] = json::array();
  for (const auto& c : g.clearances) {
    j["clearances"].push_back(
        {{"name", c.name}, {"bodies", c.bodies}, {"distance", c.distance}, {"span", spanJson(c.span)}});
  }
  j["robots"] = json::array();
  for (const auto& r : g.robots) j["robots"].push_back({{"name", r.name}, {"dof", r.dof}});
  j["enums"] = json::array();
  for (const auto& e : g.enums)
    j["enums"].push_back({{"name", e.name}, {"members", e.members}, {"span", spanJson(e.span)}});
  j["item_types"] = json::array();
  for (const auto& t : g.itemTypes) {
    json fields = json::array();
    for (const auto& f : t.fields)
      fields.push_back({{"name", f.name}, {"type", f.type.spelling}, {"type_kind", name(f.type.kind)}});
    j["item_types"].push_back({{"name", t.name}, {"fields", fields}, {"span", spanJson(t.span)}});
  }
  j["item_sets"] = json::array();
  for (const auto& s : g.itemSets) {
    json entries = json::array();
    for (const auto& e : s.entries) {
      // A JSON object's keys come out sorted: "field_order" keeps the order the entry was written in.
      json fields = json::object(), order = json::array();
      for (const auto& [name, value] : e.fields) {
        fields[name] = exprJson(value);
        order.push_back(name);
      }
      entries.push_back({{"name", e.name}, {"fields", fields}, {"field_order", order}});
    }
    j["item_sets"].push_back(
        {{"name", s.name}, {"item_type", s.itemType}, {"entries", entries}, {"span", spanJson(s.span)}});
  }
  j["constants"] = json::array();
  for (const auto& c : g.constants) {
    j["constants"].push_back({{"name", c.name},
                              {"type", c.type.spelling},
                              {"type_kind", name(c.type.kind)},
                              {"index_set", c.indexSet},
                              {"value", exprJson(c.value)},
                              {"span", spanJson(c.span)}});
  }
  j["observations"] = json::array();
  for (const auto& o : g.observations) {
    j["observations"].push_back({{"name", o.name},
                                 {"type", o.type.spelling},
                                 {"type_kind", name(o.type.kind)},
                                 {"index_set", optExpr(o.indexSet)},
                                 {"span", spanJson(o.span)}});
  }
  auto functionJson = [](const Function& f) {
    json params = json::array();
    for (const auto& p : f.params)
      params.push_back({{"name", p.name}, {"type", p.type.spelling}, {"type_kind", name(p.type.kind)}});
    json fn{{"name", f.name},
            {"kind", name(f.kind)},
            {"extern", f.isExtern},
            {"type_params", f.typeParams},
            {"params", params},
            {"result", f.result.spelling},
            {"result_kind", name(f.result.kind)},
            {"span", spanJson(f.span)}};
    if (f.body) fn["body"] = exprJson(*f.body);
    return fn;
  };
  j["feedback"] = json::array();
  for (const auto& f : g.feedback) j["feedback"].push_back(functionJson(f));
  j["functions"] = json::array();
  for (const auto& f : g.functions) j["functions"].push_back(functionJson(f));
  j["variables"] = json::array();
  for (const auto& v : g.variables) {
    json bounds = json::array();
    for (const auto& b : v.domain.bounds) bounds.push_back({{"lo", optExpr(b.lo)}, {"hi", optExpr(b.hi)}});
    j["variables"].push_back({{"id", v.id},
                              {"name", v.name},
                              {"type", v.type.spelling},
                              {"kind", name(v.type.kind)},
                              {"bounds", bounds},
                              {"set", optExpr(v.domain.set)},
                              {"init", optExpr(v.init)},
                              {"family", v.family},
                              {"index", v.indexText},
                              {"scope", v.scope},
                              {"span", spanJson(v.span)}});
  }
  j["constraints"] = json::array();
  for (const auto& c : g.constraints) {
    j["constraints"].push_back({{"id", c.id},
                                {"name", c.name},
                                {"vars", c.vars},
                                {"expr", exprJson(c.expr)},
                                {"scope", c.scope},
                                {"span", spanJson(c.span)}});
  }
  j["samplers"] = json::array();
  for (const auto& s : g.samplers) {
    json args = json::array();
    for (const auto& a : s.args) args.push_back(exprJson(a));
    j["samplers"].push_back({{"id", s.id},
                             {"sampler", s.sampler},
                             {"writes", s.writes},
                             {"reads", s.reads},
                             {"args", args},
                             {"scope", s.scope},
                             {"span", spanJson(s.span)}});
  }
  j["costs"] = json::array();
  for (const auto& c : g.costs) {
    j["costs"].push_back(
        {{"maximize", c.maximize}, {"expr", exprJson(c.expr)}, {"vars", c.vars}, {"span", spanJson(c.span)}});
  }
  j["generators"] = json::array();
  for (const auto& gen : g.generators) {
    json params = json::array(), patterns = json::array(), factors = json::array(), rules = json::array();
    for (const auto& p : gen.params)
      params.push_back({{"name", p.name}, {"type", p.type.spelling}, {"type_kind", name(p.type.kind)}});
    for (const auto& p : gen.patterns) {
      patterns.push_back({{"param", p.param},
                          {"param_index", p.paramIndex},
                          {"kind", name(p.kind)},
                          {"text", p.text},
                          {"span", spanJson(p.span)}});
    }
    for (const auto& f : gen.factors) {
      json context = json::array();
      for (const auto& c : f.context)
        context.push_back({{"name", c.name}, {"value", exprJson(c.value)}, {"params", c.params}});
      factors.push_back({{"label", f.label},
                         {"kind", name(f.kind)},
                         {"feature", optExpr(f.feature)},
                         {"lo", f.lo},
                         {"hi", f.hi},
                         {"direction", name(f.direction)},
                         {"prompt", f.prompt},
                         {"learning", f.learning},
                         {"scale", name(f.scale)},
                         {"rating", name(f.rating)},
                         {"context", context},
                         {"params", f.params},
                         {"span", spanJson(f.span)}});
    }
    // "per" names every key; "per_exprs" (one entry per key, null for a parameter or capture) holds the
    // expression keys, so that a graph without expression keys reads as before.
    json perNames = json::array(), perExprs = json::array();
    for (const auto& k : gen.perKeys) {
      perNames.push_back(k.name);
      perExprs.push_back(k.expr ? json{{"expr", exprJson(*k.expr)}, {"params", k.params}} : json(nullptr));
    }
    for (const auto& r : gen.learnRules) {
      json labels = json::array();
      for (const auto& l : r.labels) labels.push_back({{"factor", l.factor}, {"value", exprJson(l.value)}});
      rules.push_back({{"event", r.event},
                       {"binders", r.binders},
                       {"binds", r.binds},
                       {"labels", labels},
                       {"condition", optExpr(r.condition)},
                       {"span", spanJson(r.span)}});
    }
    j["generators"].push_back({{"name", gen.name},
                               {"arity", gen.params.size()},
                               {"params", params},
                               {"patterns", patterns},
                               {"captures", gen.captures},
                               {"per", perNames},
                               {"per_exprs", perExprs},
                               {"factors", factors},
                               {"guard", optExpr(gen.guard)},
                               {"accept", gen.accept},
                               {"fallback", gen.fallback},
                               {"explore", gen.exploreAccepted ? "accepted" : "anywhere"},
                               {"learn", rules},
                               {"span", spanJson(gen.span)}});
  }
  j["skills"] = g.skills;
  j["tasks"] = json::array();
  for (const auto& t : g.tasks) {
    json instances = json::array();
    for (const auto& si : t.instances) {
      json actions = json::array();
      for (const auto& a : si.actions) actions.push_back(actionJson(a));
      instances.push_back({{"skill", si.skill},
                           {"name", si.name},
                           {"vars", si.vars},
                           {"params", si.params},
                           {"constraints", si.constraints},
                           {"samplers", si.samplers},
                           {"actions", actions},
                           {"span", spanJson(si.span)}});
    }
    j["tasks"].push_back({{"name", t.name},
                          {"implicit", t.implicit},
                          {"vars", t.vars},
                          {"constraints", t.constraints},
                          {"samplers", t.samplers},
                          {"costs", t.costs},
                          {"instances", instances},
                          {"span", spanJson(t.span)}});
  }
  return j.dump(1) + "\n";
}

}  // namespace cbtl::ir
