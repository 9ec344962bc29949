// toDot (GraphPrinter.h): the constraint graph for Graphviz, one cluster per task, so that a variable every task
// includes is drawn once per task under that task's name. Inside a task: variables (ellipses), hard constraints
// (boxes, an edge per variable they read), samplers (diamonds, an arrow to each variable they write, a dotted line
// from each they read), and the personalized constraints a generator would create (dashed rounded boxes, a dashed
// edge to each variable its patterns match there). Clearances constrain every motion, not variables: octagons
// outside the tasks.
#include "ir/GraphPrinter.h"

#include "ir/GeneratorMatch.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <map>
#include <set>
#include <sstream>

namespace cbtl::ir {
namespace {

std::string quoted(const std::string& text) { return nlohmann::json(text).dump(); }

const char* factorKindName(FactorKind k) {
  switch (k) {
    case FactorKind::Interval:
      return "interval";
    case FactorKind::Threshold:
      return "threshold";
    case FactorKind::Table:
      return "table";
    case FactorKind::Text:
      return "text";
  }
  return "?";
}

void taskBody(const ConstraintGraph& g, const Task& task, std::size_t t, const std::string& indent,
              std::ostringstream& o) {
  for (VarId v : task.vars) {
    const Variable& var = g.variables.at(v);
    o << fmt::format("{}t{}v{} [shape=ellipse, label={}];\n", indent, t, v,
                     quoted(var.name + " : " + var.type.spelling));
  }
  for (std::uint32_t c : task.constraints) {
    const Constraint& con = g.constraints.at(c);
    o << fmt::format("{}t{}c{} [shape=box, label={}];\n", indent, t, c, quoted(con.name));
    for (VarId v : con.vars) o << fmt::format("{}t{}c{} -- t{}v{};\n", indent, t, c, t, v);
  }
  for (std::uint32_t s : task.samplers) {
    const Sampler& sam = g.samplers.at(s);
    o << fmt::format("{}t{}s{} [shape=diamond, label={}];\n", indent, t, s, quoted("~ " + sam.sampler));
    for (VarId v : sam.writes) o << fmt::format("{}t{}s{} -- t{}v{} [dir=forward];\n", indent, t, s, t, v);
    for (VarId v : sam.reads) o << fmt::format("{}t{}v{} -- t{}s{} [style=dotted, dir=forward];\n", indent, t, v, t, s);
  }
  for (std::size_t i = 0; i < g.generators.size(); ++i) {
    const Generator& gen = g.generators[i];
    const std::set<VarId> matched = variablesMatchedBy(g, gen, task.vars);
    if (matched.empty()) continue;
    std::string kinds;
    for (const auto& f : gen.factors) kinds += (kinds.empty() ? "" : ", ") + std::string(factorKindName(f.kind));
    o << fmt::format("{}t{}p{} [shape=box, style=\"dashed,rounded\", label={}];\n", indent, t, i,
                     quoted("personalized: " + gen.name + (kinds.empty() ? "" : " (" + kinds + ")")));
    for (VarId v : matched) o << fmt::format("{}t{}p{} -- t{}v{} [style=dashed];\n", indent, t, i, t, v);
  }
}

}  // namespace

std::string toDot(const ConstraintGraph& g) {
  std::ostringstream o;
  o << "graph cbtl {\n  graph [rankdir=LR];\n";
  for (std::size_t t = 0; t < g.tasks.size(); ++t) {
    const Task& task = g.tasks[t];
    // A file without tasks has one implicit task: no frame around it.
    if (task.implicit) {
      taskBody(g, task, t, "  ", o);
      continue;
    }
    o << fmt::format("  subgraph cluster_t{} {{\n    label={};\n    style=rounded;\n", t, quoted("task " + task.name));
    taskBody(g, task, t, "    ", o);
    o << "  }\n";
  }
  for (std::size_t i = 0; i < g.clearances.size(); ++i) {
    std::string bodies;
    for (const auto& b : g.clearances[i].bodies) bodies += (bodies.empty() ? "" : ", ") + quoted(b);
    o << fmt::format(
        "  k{} [shape=octagon, label={}];\n", i,
        quoted(fmt::format("clearance {}: {} >= {} m", g.clearances[i].name, bodies, g.clearances[i].distance)));
  }
  o << "}\n";
  return o.str();
}

}  // namespace cbtl::ir
