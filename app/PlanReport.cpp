#include "app/PlanReport.h"

#include "runtime/solver/PersonalExplanation.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace cbtl::app {

namespace {

std::string renderValue(const sim::Value& a) {
  switch (a.kind) {
    case sim::Value::Kind::Name:
      return a.text;
    case sim::Value::Kind::Number:
      return fmt::format("{:.6g}", a.number);
    case sim::Value::Kind::Vector: {
      std::string s = "(";
      for (std::size_t k = 0; k < a.vector.size(); ++k) s += fmt::format("{}{:.6g}", k ? ", " : "", a.vector[k]);
      return s + ")";
    }
    case sim::Value::Kind::Names: {
      std::string s = "{";
      for (std::size_t k = 0; k < a.members.size(); ++k) s += (k ? ", " : "") + a.members[k];
      return s + "}";
    }
  }
  return {};
}

std::string renderArgs(const std::string& name, const std::vector<sim::Value>& args) {
  std::string s = name + "(";
  for (std::size_t i = 0; i < args.size(); ++i) s += (i ? ", " : "") + renderValue(args[i]);
  return s + ")";
}

// The variables of the constraints that rejected candidates which no sampler of the CSP writes: the solver moves
// variables only through samplers, so these kept their starting value in every candidate (cbtlc's W0503 says the
// same before any run). Often the whole reason a small program "cannot be solved".
void printFrozenVariables(std::FILE* out, const solver::Csp& csp, const solver::SolveResult& r) {
  if (csp.program == nullptr) return;
  const rt::Program& program = *csp.program;
  const ir::ConstraintGraph& graph = program.graph();
  std::vector<bool> written(graph.variables.size(), false);
  for (std::uint32_t s : csp.samplers) {
    for (ir::VarId v : graph.samplers.at(s).writes) written.at(v) = true;
  }
  std::vector<ir::VarId> frozen;
  for (const solver::ConstraintStats& s : r.constraints) {
    if (s.rejections == 0 || s.ref.kind != solver::ConstraintKind::Hard) continue;
    for (ir::VarId v : graph.constraints.at(s.ref.index).vars) {
      if (!written.at(v) && std::find(frozen.begin(), frozen.end(), v) == frozen.end()) frozen.push_back(v);
    }
  }
  if (frozen.empty()) return;
  fmt::print(out, "  never changed (no sampler writes them, so every candidate kept its starting value):\n");
  for (ir::VarId v : frozen) {
    const rt::VarSlot& slot = program.slot(v);
    fmt::print(out, "    {} = {}  ({}; add 'sample {} ~ ...;')\n", graph.variables[v].name,
               slot.offset + slot.type.width <= csp.initial.size()
                   ? program.render(slot.type, csp.initial.data() + slot.offset)
                   : std::string("?"),
               rt::Program::where(graph.variables[v].span), graph.variables[v].name);
  }
}

void printStatistics(std::FILE* out, const solver::Csp& csp, const solver::SolveResult& r, const std::string& title) {
  using namespace cbtl::solver;
  fmt::print(out, "{}: {} after {} iterations ({} candidates checked, {} pruned by cost, {} improvements)\n", title,
             toString(r.outcome), r.iterations, r.candidatesChecked, r.prunedByCost, r.improvements);
  std::vector<ConstraintStats> stats = r.constraints;
  std::stable_sort(stats.begin(), stats.end(),
                   [](const auto& a, const auto& b) { return a.rejections > b.rejections; });
  fmt::print(out, "  {:>10} {:>11}  {:<48} {}\n", "rejected", "evaluated", "constraint", "declared at");
  for (const auto& s : stats) {
    if (s.evaluations == 0 && s.rejections == 0) continue;
    fmt::print(out, "  {:>10} {:>11}  {:<48} {}\n", s.rejections, s.evaluations, constraintName(csp, s.ref),
               constraintLocation(csp, s.ref));
  }
  // The solver re-evaluates a constraint only when a variable it reads changed (Solver.h); its cached result still
  // rejects every candidate it is first to fail, so the two counts differ in a way worth one line.
  if (std::any_of(stats.begin(), stats.end(), [](const auto& s) { return s.rejections > s.evaluations; }))
    fmt::print(out,
               "  (rejected can exceed evaluated: a constraint whose variables did not change keeps its cached "
               "result, which rejects again without a new evaluation)\n");
  if (r.outcome != SolveOutcome::Solved) printFrozenVariables(out, csp, r);
  // A robot world's every collision check keeps the program's clearances: when the search failed, they may be why
  // (a constraint such as confCollisionFree rejects what comes too close), so say them with where they stand.
  if (r.outcome != SolveOutcome::Solved && csp.program != nullptr) {
    for (const ir::Clearance& c : csp.program->graph().clearances)
      fmt::print(out, "  every collision check keeps clearance {}: {:g} mm from {} ({})\n", c.name, c.distance * 1e3,
                 fmt::join(c.bodies, ", "), rt::Program::where(c.span));
  }
  if (r.planFailures.empty()) return;
  std::vector<std::pair<std::string, PlanFailure>> failures(r.planFailures.begin(), r.planFailures.end());
  std::stable_sort(failures.begin(), failures.end(),
                   [](const auto& a, const auto& b) { return a.second.count > b.second.count; });
  fmt::print(out, "  {} rejections by failing action (the first detail of each):\n", kPlanExecutesName);
  for (const auto& [what, f] : failures)
    fmt::print(out, "  {:>10}  {}{}\n", f.count, what, f.example.empty() ? "" : " (" + f.example + ")");
}

}  // namespace

std::string renderCall(const sim::ActionCall& call) {
  std::string s = renderArgs(call.name, call.args);
  // The exceptions to the clearances the call runs under, as the skill's `allow` said them (innermost last).
  for (const sim::ClearanceException& e : call.exceptions) {
    std::string names;
    for (const std::string& n : e.names) names += (names.empty() ? "" : ", ") + n;
    s += e.separation < 0 ? fmt::format("  [allow {} touch {} {:g} mm]", e.part, names, -e.separation * 1e3)
                          : fmt::format("  [allow {} near {} {:g} mm]", e.part, names, e.separation * 1e3);
  }
  return s;
}

std::string renderEvent(const sim::FeedbackEvent& event, const ir::ConstraintGraph* graph) {
  if (graph == nullptr) return renderArgs(event.name, event.args);
  const auto declared = std::find_if(graph->feedback.begin(), graph->feedback.end(),
                                     [&](const ir::Function& f) { return f.name == event.name; });
  if (declared == graph->feedback.end()) return renderArgs(event.name, event.args);
  std::vector<sim::Value> args = event.args;
  for (std::size_t i = 0; i < args.size() && i < declared->params.size(); ++i) {
    if (declared->params[i].type.kind == ir::TypeKind::Bool && args[i].kind == sim::Value::Kind::Number)
      args[i] = sim::Value::name(args[i].number != 0 ? "true" : "false");
  }
  return renderArgs(event.name, args);
}

void printSolution(std::FILE* out, const approach::Plan& plan) {
  const rt::Program& program = *plan.csp.program;
  const ir::Task& task = *plan.csp.task;
  fmt::print(
      out, "task {}: {}{}\n", task.name, solver::toString(plan.solve.outcome),
      plan.replanned ? " (replanned without personalized constraints: the user's preferences cannot be met)" : "");
  if (!plan.ok) return;
  for (ir::VarId v : task.vars) {
    const auto& slot = program.slot(v);
    fmt::print(out, "  {} = {}\n", program.graph().variables[v].name,
               program.render(slot.type, plan.solve.assignment.data() + slot.offset));
  }
  fmt::print(out, "plan ({} call{}):\n", plan.calls.size(), plan.calls.size() == 1 ? "" : "s");
  for (const auto& c : plan.calls) fmt::print(out, "  {}\n", renderCall(c));
}

void printSolveStatistics(std::FILE* out, const approach::Plan& plan) {
  for (const auto& [budget, result] : plan.failedTiers)
    printStatistics(out, plan.csp, result, fmt::format("dry-run tier with {} planner iterations per motion", budget));
  if (plan.dryRun())
    fmt::print(out, "dry-run tier of the result: {} planner iterations per motion\n", plan.motionIterations);
  if (plan.failedFull) printStatistics(out, plan.csp, *plan.failedFull, "with personalized constraints");
  printStatistics(out, plan.csp, plan.solve, plan.failedFull ? "replanned without personalized constraints" : "solve");
  rt::BuiltinHost* host = plan.csp.program->host();
  if (!plan.dryRun() && host != nullptr && host->executionModel() != nullptr)
    fmt::print(out, "note: the plan was not dry-run: the world model does not know every action of the task\n");
}

std::string renderObserved(const rt::Program& program, const rt::ValueType& type, const double* v) {
  if (type.kind != rt::ValueKind::Set) return program.render(type, v);
  const rt::ValueType element = program.setElementType(type);
  std::string text;
  for (std::size_t i = 0; i < program.setElementCount(type); ++i) {
    const double member = static_cast<double>(i);
    if (v[i] != 0) text += (text.empty() ? "" : ", ") + program.render(element, &member);
  }
  return "{" + text + "}";
}

void printObservation(std::FILE* out, const rt::Program& program, const std::vector<double>& observation) {
  if (program.observationSlots().empty()) return;
  fmt::print(out, "observed:\n");
  for (const auto& [name, slot] : program.observationSlots()) {
    if (slot.offset + slot.type.width > observation.size()) continue;
    fmt::print(out, "  {} = {}\n", name, renderObserved(program, slot.type, observation.data() + slot.offset));
  }
}

void printPersonal(std::FILE* out, const approach::Plan& plan, const std::vector<double>& assignment,
                   const std::string& heading) {
  const auto instances = solver::explainPersonal(plan.csp, assignment);
  if (instances.empty()) return;
  fmt::print(out, "{}:\n", heading);
  fmt::print(out, "  {:<8} {:>7} {:>7} {:>8} {:>6}  {}\n", "", "P", "accept", "entropy", "data", "instance");
  for (const auto& e : instances) {
    const char* status = !e.reached ? "unjudged" : !e.applies ? "n/a" : e.holds ? "holds" : "fails";
    // No labelled example yet: P is the declared prior's reading, not something learned about this person.
    // Unjudged: no P or entropy to show (the state they are read in is not reached).
    const std::string p = e.reached ? fmt::format("{:.3f}", e.probability) : "-";
    const std::string entropy = e.reached ? fmt::format("{:.3f}", e.entropyBits) : "-";
    fmt::print(out, "  {:<8} {:>7} {:>7.3f} {:>8} {:>6}  {}{}{}{}{}\n", status, p, e.accept, entropy, e.evidence,
               e.name, e.key.empty() ? "" : " [" + e.key + "]", e.inCsp ? "" : " (not in this CSP)",
               e.evidence == 0 ? " (no data: the prior, not learned)" : "",
               e.reached ? "" : " (its skill's start state is not reached with these values: no verdict)");
    for (const auto& t : e.text) {
      fmt::print(out, "           {} = {}{}\n", t.factor, t.subject, t.context.empty() ? "" : " in " + t.context);
      fmt::print(out, "           theta: {}\n", t.theta);
    }
  }
}

void printRecheck(std::FILE* out, const approach::Plan& plan) {
  if (!plan.rechecked) return;
  fmt::print(out, "re-check: {} constraints and {} variables evaluated from scratch: {}\n",
             plan.recheck.constraintsChecked, plan.recheck.variablesChecked,
             plan.recheck.holds() ? "all hold" : "VIOLATED");
}

}  // namespace cbtl::app
