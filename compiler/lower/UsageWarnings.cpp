#include "compiler/lower/UsageWarnings.h"

#include "ir/GeneratorMatch.h"
#include "ir/ReadSet.h"

#include <fmt/format.h>

#include <map>
#include <set>

namespace cbtl {
namespace {

void varsOf(const ir::ConstraintGraph& g, const ir::Action& a, std::set<ir::VarId>& out) {
  for (const auto& x : a.args) ir::collectReadVars(g, x, out);
  if (a.set) ir::collectReadVars(g, *a.set, out);
  if (a.condition) ir::collectReadVars(g, *a.condition, out);
  if (a.allow && a.allow->target) ir::collectReadVars(g, *a.allow->target, out);
  for (const auto& b : a.body) varsOf(g, b, out);
  for (const auto& b : a.elseBody) varsOf(g, b, out);
}

// True when the solver can draw a value for the variable without a sampler: finite types, Conf<R> (joint
// limits), and any variable whose declaration bounds every component or lists its values.
bool hasBoundedDomain(const ir::Variable& v) {
  const ir::TypeKind k = v.type.kind;
  if (k == ir::TypeKind::Bool || k == ir::TypeKind::Enum || k == ir::TypeKind::Item || k == ir::TypeKind::Conf)
    return true;
  if (v.domain.set) return true;
  if (v.domain.bounds.empty()) return false;
  for (const auto& b : v.domain.bounds) {
    if (!b.lo || !b.hi) return false;
  }
  return true;
}

}  // namespace

void reportUsageWarnings(const ir::ConstraintGraph& graph, const std::vector<const VarDecl*>& declOf,
                         DiagnosticEngine& diags) {
  std::set<ir::VarId> read, written;
  for (const auto& c : graph.constraints) read.insert(c.vars.begin(), c.vars.end());
  for (const auto& s : graph.samplers) {
    read.insert(s.reads.begin(), s.reads.end());
    written.insert(s.writes.begin(), s.writes.end());
  }
  for (const auto& c : graph.costs) read.insert(c.vars.begin(), c.vars.end());
  std::vector<ir::VarId> all;
  for (const auto& v : graph.variables) all.push_back(v.id);
  for (const auto& gen : graph.generators) {
    const std::set<ir::VarId> matched = ir::variablesMatchedBy(graph, gen, all);
    read.insert(matched.begin(), matched.end());  // the personalized constraints it creates read them
  }
  for (const auto& t : graph.tasks) {
    for (const auto& inst : t.instances) {
      for (const auto& a : inst.actions) varsOf(graph, a, read);
    }
  }

  // Declarations in the order of their first variable, so the warnings come out in a stable order.
  std::vector<const VarDecl*> order;
  std::map<const VarDecl*, std::vector<ir::VarId>> members;
  for (ir::VarId id = 0; id < declOf.size() && id < graph.variables.size(); ++id) {
    const VarDecl* d = declOf[id];
    if (d == nullptr) continue;
    auto& ids = members[d];
    if (ids.empty()) order.push_back(d);
    ids.push_back(id);
  }

  for (const VarDecl* d : order) {
    bool used = false, unproducible = false, frozen = false, bounded = true;
    for (ir::VarId id : members[d]) {
      if (!read.count(id)) continue;
      used = true;
      const ir::Variable& v = graph.variables[id];
      if (written.count(id)) continue;
      // Only samplers move a variable: without one, every candidate keeps the initial assignment.
      if (!v.init && !hasBoundedDomain(v)) {
        unproducible = true;
      } else {
        frozen = true;
        bounded = bounded && hasBoundedDomain(v);
      }
    }
    if (!used) {
      diags.warning("W0201", d->name.range, fmt::format("variable '{}' is never used", d->name.name))
          .help("no constraint, sampler, cost or action reads it; use it or remove it");
    } else if (unproducible) {
      diags
          .warning("W0502", d->name.range,
                   fmt::format("variable '{}' has no sampler, no initial value and an unbounded domain", d->name.name))
          .help(
              fmt::format("add 'sample {} ~ ...;', an initial value '= ...', or bound it with 'in ...'", d->name.name));
    } else if (frozen) {
      // Without `= init` it starts at zero moved into its domain (Program::initialAssignment).
      const std::string start =
          d->init ? "its initial value" : "its starting value (zero, or its domain's nearest bound or first member)";
      diags
          .warning("W0503", d->name.range,
                   fmt::format("variable '{}' is never sampled, so every solution keeps {}", d->name.name, start))
          .help(bounded
                    ? fmt::format("let the solver choose it with 'sample {} ~ uniform;' (over its declared domain), "
                                  "or declare it 'const' if it is fixed",
                                  d->name.name)
                    : fmt::format("let the solver choose it with 'sample {} ~ uniformReal(lo, hi);' (or bound it "
                                  "with 'in ...' and sample it '~ uniform'), or declare it 'const' if it is fixed",
                                  d->name.name));
    }
  }
}

}  // namespace cbtl
