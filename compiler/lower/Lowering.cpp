// The `lower` entry point and the order of the pass, read sets and the graph-size limits; the other
// concerns of the lowerer are implemented in the Lowering*.cpp files listed in LoweringInternal.h.
#include "compiler/lower/Lowering.h"

#include "compiler/lower/LoweringInternal.h"
#include "compiler/lower/UsageWarnings.h"
#include "ir/ReadSet.h"

#include <fmt/format.h>

namespace cbtl {
namespace detail {

void Lowerer::run(const std::vector<std::unique_ptr<Module>>& modules) {
  g_.domain = symbols_.domainName;
  if (symbols_.world) g_.world = symbols_.world->path;
  if (symbols_.simulator) {
    g_.simulator = symbols_.simulator->command;
    g_.simulatorSpan = span(symbols_.simulator->range);
  }
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

ir::Span Lowerer::span(SourceRange r) const {
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

void Lowerer::followCallsInReadSets() {
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

std::size_t Lowerer::nodeCount(const ir::Expr& x) const {
  std::size_t n = 1;
  if (x.op == ir::Op::Call) {
    if (const auto it = inlinedNodes_.find(x.text); it != inlinedNodes_.end()) n += it->second;
  }
  for (const auto& c : x.children) n += nodeCount(c);
  return n;
}

std::size_t Lowerer::actionSize(const ir::Action& a) const {
  std::size_t n = 1 + (a.set ? nodeCount(*a.set) : 0) + (a.condition ? nodeCount(*a.condition) : 0);
  if (a.allow && a.allow->target) n += nodeCount(*a.allow->target);
  for (const auto& x : a.args) n += nodeCount(x);
  for (const auto& b : a.body) n += actionSize(b);
  for (const auto& b : a.elseBody) n += actionSize(b);
  return n;
}

bool Lowerer::grow(std::size_t units, SourceRange at) {
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

void Lowerer::tooManyMembers(SourceRange at, const char* what) {
  diags_.error("E0317", at, fmt::format("{} may have at most {} members", what, kMaxSetSize));
}

}  // namespace detail

bool lowerToGraph(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                  const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& graph) {
  const std::size_t before = diags.errorCount();
  detail::Lowerer(symbols, sources, diags, graph).run(modules);
  return diags.errorCount() == before;
}

}  // namespace cbtl
