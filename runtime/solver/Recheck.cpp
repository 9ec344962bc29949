#include "runtime/solver/Recheck.h"

#include "runtime/solver/PersonalEvaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace cbtl::solver {
namespace {

bool isInteger(double v) { return std::isfinite(v) && std::floor(v) == v; }

// Type facts of one variable's value: what any value of the type must satisfy whatever its domain says.
std::string typeViolation(const rt::Program& program, const rt::ValueType& t, const double* v) {
  for (std::size_t i = 0; i < t.width; ++i) {
    if (t.kind != rt::ValueKind::Text && !std::isfinite(v[i])) return fmt::format("component {} is {}", i, v[i]);
  }
  switch (t.kind) {
    case rt::ValueKind::Bool:
      return v[0] == 0 || v[0] == 1 ? "" : fmt::format("{} is not a boolean", v[0]);
    case rt::ValueKind::Int:
      return isInteger(v[0]) ? "" : fmt::format("{} is not an integer", v[0]);
    case rt::ValueKind::Enum:
    case rt::ValueKind::Item: {
      const std::size_t count = program.setElementCount(rt::ValueType{rt::ValueKind::Set, 0, t.typeName});
      return isInteger(v[0]) && v[0] >= 0 && v[0] < static_cast<double>(count)
                 ? ""
                 : fmt::format("{} is not a member index of {}", v[0], t.typeName);
    }
    case rt::ValueKind::Text:
      return isInteger(v[0]) && v[0] >= 0 && v[0] < static_cast<double>(program.strings().size())
                 ? ""
                 : "not an interned text";
    default:
      return "";
  }
}

std::string domainViolation(const rt::Program& program, const rt::DomainCheck& d, const double* v,
                            const rt::EvalContext& ctx) {
  const auto& pool = program.pool();
  for (std::size_t c = 0; c < d.lo.size(); ++c) {
    if (d.lo[c] != UINT32_MAX && !(v[c] >= pool.evalScalar(d.lo[c], ctx))) {
      return fmt::format("component {} = {} is below its bound {}", c, v[c], pool.evalScalar(d.lo[c], ctx));
    }
    if (d.hi[c] != UINT32_MAX && !(v[c] <= pool.evalScalar(d.hi[c], ctx))) {
      return fmt::format("component {} = {} is above its bound {}", c, v[c], pool.evalScalar(d.hi[c], ctx));
    }
  }
  if (d.members && std::find(d.members->begin(), d.members->end(), v[0]) == d.members->end()) {
    return fmt::format("{} is not in its declared set", v[0]);
  }
  return "";
}

}  // namespace

RecheckResult recheck(const Csp& csp, const std::vector<double>& assignment) {
  RecheckResult r;
  const rt::Program& program = *csp.program;
  const auto& graph = program.graph();
  if (assignment.size() != program.assignmentWidth()) {
    r.violations.push_back(
        fmt::format("the assignment has {} values, the program {}", assignment.size(), program.assignmentWidth()));
    return r;
  }
  std::vector<double> x = assignment, obs = csp.observation;
  x.resize(std::max<std::size_t>(x.size(), 1), 0.0);
  obs.resize(std::max<std::size_t>(program.observationWidth(), 1), 0.0);
  std::vector<double> frame(std::max<std::size_t>(program.frameSize(), 1), 0.0);
  const rt::EvalContext ctx{x.data(), obs.data(), frame.data(), program.callContext()};

  for (ir::VarId v : csp.task->vars) {
    const rt::VarSlot& slot = program.slot(v);
    ++r.variablesChecked;
    std::string why = typeViolation(program, slot.type, x.data() + slot.offset);
    if (why.empty()) why = domainViolation(program, program.domainCheck(v), x.data() + slot.offset, ctx);
    if (!why.empty()) {
      r.violations.push_back(fmt::format("variable '{}' ({}): {}", graph.variables[v].name,
                                         rt::Program::where(graph.variables[v].span), why));
    }
  }
  // In a staged plan each constraint is evaluated in the state its skill starts in, unrolled afresh.
  std::map<std::uint32_t, std::uint32_t> stageOfConstraint;
  for (std::size_t i = 0; i < csp.constraints.size() && i < csp.constraintStage.size(); ++i) {
    if (csp.constraints[i].kind == ConstraintKind::Hard)
      stageOfConstraint[csp.constraints[i].index] = csp.constraintStage[i];
  }
  if (csp.plan != nullptr) csp.plan->changed();
  const auto enter = [&](std::uint32_t stage) {
    return csp.plan == nullptr || stage == kAnyStage || csp.plan->enterStage(stage, ctx);
  };
  for (std::uint32_t c : csp.task->constraints) {
    ++r.constraintsChecked;
    const auto stage = stageOfConstraint.find(c);
    if (!enter(stage == stageOfConstraint.end() ? 0 : stage->second) ||
        !program.pool().evalBool(program.constraints()[c].root, ctx)) {
      r.violations.push_back(fmt::format("constraint '{}' ({}) does not hold", graph.constraints[c].name,
                                         rt::Program::where(graph.constraints[c].span)));
    }
  }
  // The personalized constraints the CSP enforces: all of them when it personalizes, and in CBTL's exploration
  // those whose generator explores only where it accepts (Csp.h).
  std::optional<PersonalEvaluator> fresh;  // a new evaluator: nothing cached
  for (const ConstraintRef& c : csp.constraints) {
    if (!c.personal()) continue;
    if (!fresh) fresh.emplace(program, *csp.instances, *csp.user);
    const std::uint32_t i = c.index;
    ++r.constraintsChecked;
    if (!enter(i < csp.instanceStage.size() ? csp.instanceStage[i] : 0)) {
      // Not the constraint's verdict: the state it is judged in is never reached (PersonalExplanation.h says the same).
      const sim::PlanVerdict v = csp.plan->stageFailure();
      r.violations.push_back(fmt::format(
          "personalized constraint '{}' cannot be judged: the state it is judged in is not reached (call {}, {}: {})",
          (*csp.instances)[i].name, v.failedCall + 1, v.action, v.status));
    } else if (!fresh->holds(i, fresh->evaluate(i, ctx))) {
      r.violations.push_back(fmt::format("personalized constraint '{}' does not hold", (*csp.instances)[i].name));
    }
  }
  if (csp.plan != nullptr) {
    ++r.constraintsChecked;
    const sim::PlanVerdict v = csp.plan->check(ctx);
    if (!v.executes) {
      r.violations.push_back(fmt::format("the plan does not execute: call {} ({}): {}{}", v.failedCall + 1, v.action,
                                         v.status, v.detail.empty() ? "" : ": " + v.detail));
    }
    csp.plan->enterStage(0, ctx);
  }
  return r;
}

}  // namespace cbtl::solver
