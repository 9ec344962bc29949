#include "ir/Validator.h"

#include "ir/OpNames.h"
#include "ir/Pattern.h"
#include "ir/ReadSet.h"

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace cbtl::ir {
namespace {

// The allow actions of an action tree: each has exactly one of a clearance and a target, names a declared
// clearance, keeps a finite separation, and covers at least one action; no other action has an allowance.
void validateActions(const std::vector<Action>& actions, const std::set<std::string>& clearances,
                     const std::string& where, std::vector<std::string>& problems) {
  for (const auto& a : actions) {
    if (a.kind != ActionKind::Allow) {
      if (a.allow) problems.push_back(fmt::format("{}: a {} action has an allowance", where, name(a.kind)));
    } else if (!a.allow) {
      problems.push_back(fmt::format("{}: an allow action has no allowance", where));
    } else {
      const Allowance& al = *a.allow;
      if (al.clearance.empty() == !al.target.has_value())
        problems.push_back(fmt::format("{}: an allowance needs exactly one of a clearance and a target", where));
      if (!al.clearance.empty() && !clearances.count(al.clearance))
        problems.push_back(fmt::format("{}: an allowance names the undeclared clearance {}", where, al.clearance));
      if (!std::isfinite(al.separation))
        problems.push_back(fmt::format("{}: an allowance's separation is not finite", where));
      if (a.body.empty()) problems.push_back(fmt::format("{}: an allow action covers no action", where));
    }
    validateActions(a.body, clearances, where, problems);
    validateActions(a.elseBody, clearances, where, problems);
  }
}

}  // namespace

std::vector<std::string> validate(const ConstraintGraph& g) {
  std::vector<std::string> problems;
  std::set<std::string> clearances;
  for (const auto& c : g.clearances) {
    if (!clearances.insert(c.name).second) problems.push_back(fmt::format("clearance {} is declared twice", c.name));
    if (!std::isfinite(c.distance) || c.distance < 0)
      problems.push_back(fmt::format("clearance {}: distance {} is not a finite number >= 0", c.name, c.distance));
    if (c.bodies.empty()) problems.push_back(fmt::format("clearance {} names no body", c.name));
    if (c.span.line == 0) problems.push_back(fmt::format("clearance {} has no span", c.name));
  }
  const auto n = g.variables.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (g.variables[i].id != i) problems.push_back(fmt::format("variable {} has id {}", i, g.variables[i].id));
    if (g.variables[i].span.line == 0) problems.push_back(fmt::format("variable {} has no span", g.variables[i].name));
  }
  for (std::size_t i = 0; i < g.constraints.size(); ++i) {
    const auto& c = g.constraints[i];
    if (c.id != i) problems.push_back(fmt::format("constraint {} has id {}", i, c.id));
    std::set<VarId> read;
    collectReadVars(g, c.expr, read);
    for (VarId v : read) {
      if (v >= n) problems.push_back(fmt::format("constraint {} reads unknown variable {}", c.name, v));
    }
    if (std::set<VarId>(c.vars.begin(), c.vars.end()) != read) {
      problems.push_back(
          fmt::format("constraint {}: hyperedge differs from the variables its expression reads", c.name));
    }
    if (c.span.line == 0) problems.push_back(fmt::format("constraint {} has no span", c.name));
    if (c.expr.type.kind != TypeKind::Bool && c.expr.type.kind != TypeKind::Error) {
      problems.push_back(fmt::format("constraint {} is {}, not bool", c.name, c.expr.type.spelling));
    }
  }
  for (const auto& s : g.samplers) {
    if (s.writes.empty()) problems.push_back(fmt::format("sampler #{} ({}) writes no variable", s.id, s.sampler));
    for (VarId v : s.writes) {
      if (v >= n) problems.push_back(fmt::format("sampler #{} writes unknown variable {}", s.id, v));
    }
  }
  for (const auto& t : g.tasks) {
    std::set<VarId> vars(t.vars.begin(), t.vars.end());
    std::set<std::string> names;
    for (VarId v : t.vars) {
      if (v >= n) {
        problems.push_back(fmt::format("task {} lists unknown variable {}", t.name, v));
        continue;
      }
      if (!names.insert(g.variables[v].name).second) {
        problems.push_back(fmt::format("task {} has two variables named {}", t.name, g.variables[v].name));
      }
    }
    for (auto c : t.constraints) {
      if (c >= g.constraints.size()) {
        problems.push_back(fmt::format("task {} lists unknown constraint {}", t.name, c));
        continue;
      }
      for (VarId v : g.constraints[c].vars) {
        if (!vars.count(v))
          problems.push_back(
              fmt::format("task {}: constraint {} reads a variable outside the task", t.name, g.constraints[c].name));
      }
    }
    for (auto s : t.samplers) {
      if (s >= g.samplers.size()) {
        problems.push_back(fmt::format("task {} lists unknown sampler {}", t.name, s));
        continue;
      }
      for (VarId v : g.samplers[s].writes) {
        if (!vars.count(v))
          problems.push_back(fmt::format("task {}: sampler #{} writes a variable outside the task", t.name, s));
      }
    }
    for (auto c : t.costs) {
      if (c >= g.costs.size()) problems.push_back(fmt::format("task {} lists unknown cost {}", t.name, c));
    }
    for (const auto& si : t.instances)
      validateActions(si.actions, clearances, fmt::format("task {}, {}", t.name, si.name), problems);
  }
  for (const auto& gen : g.generators) {
    for (const auto& p : gen.patterns) {
      std::string error;
      std::size_t at = 0;
      const bool ok = p.kind == PatternKind::Glob ? parseGlob(p.text, error, at).has_value()
                                                  : compileRegex(p.text, error).has_value();
      if (!ok)
        problems.push_back(fmt::format("generator {}: pattern {} does not compile: {}", gen.name, p.text, error));
      if (p.paramIndex >= gen.params.size())
        problems.push_back(fmt::format("generator {}: pattern for unknown parameter", gen.name));
    }
    if (gen.params.empty()) problems.push_back(fmt::format("generator {} has arity 0", gen.name));
  }
  return problems;
}

}  // namespace cbtl::ir
