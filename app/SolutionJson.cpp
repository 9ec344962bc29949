#include "app/SolutionJson.h"

#include "runtime/approach/ValueBridge.h"
#include "runtime/solver/PersonalExplanation.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace cbtl::app {

namespace {

using ordered = nlohmann::ordered_json;

ordered simValueJson(const sim::Value& v) {
  switch (v.kind) {
    case sim::Value::Kind::Number:
      return v.number;
    case sim::Value::Kind::Vector:
      return v.vector;
    case sim::Value::Kind::Name:
      return v.text;
    case sim::Value::Kind::Names:
      return v.members;
  }
  return nullptr;
}

ordered valueJson(const rt::Program& program, const rt::ValueType& type, const double* v) {
  switch (type.kind) {
    case rt::ValueKind::Bool:
      return v[0] != 0;
    case rt::ValueKind::Int:
      return static_cast<long long>(std::llround(v[0]));
    case rt::ValueKind::Set: {
      const rt::ValueType element = program.setElementType(type);
      ordered members = ordered::array();
      for (std::size_t i = 0; i < program.setElementCount(type); ++i) {
        const double member = static_cast<double>(i);
        if (v[i] != 0) members.push_back(program.render(element, &member));
      }
      return members;
    }
    default:
      return simValueJson(approach::toSimValue(program, type, v));
  }
}

}  // namespace

const char* solveStatus(const approach::Plan& plan) {
  if (plan.solve.outcome == solver::SolveOutcome::Interrupted) return "interrupted";
  if (plan.refused()) return "refused";
  return plan.ok ? "solved" : "unsatisfiable";
}

std::string solutionJson(const approach::Plan& plan, const std::vector<double>& observation) {
  const rt::Program& program = *plan.csp.program;
  const ir::Task& task = *plan.csp.task;
  ordered j;
  j["format"] = "cbtl-solution";
  j["version"] = 1;
  j["task"] = task.name;
  j["status"] = solveStatus(plan);
  j["outcome"] = solver::toString(plan.solve.outcome);
  j["replanned"] = plan.replanned;
  j["iterations"] = plan.iterations;
  if (plan.ok) {
    ordered assignment = ordered::object();
    for (ir::VarId v : task.vars) {
      const auto& slot = program.slot(v);
      assignment[program.graph().variables[v].name] =
          valueJson(program, slot.type, plan.solve.assignment.data() + slot.offset);
    }
    j["assignment"] = std::move(assignment);
    ordered calls = ordered::array();
    for (const auto& c : plan.calls) {
      ordered args = ordered::array();
      for (const auto& a : c.args) args.push_back(simValueJson(a));
      calls.push_back({{"action", c.name}, {"args", std::move(args)}});
    }
    j["plan"] = std::move(calls);
  }
  if (plan.rechecked)
    j["recheck"] = {{"constraints", plan.recheck.constraintsChecked},
                    {"variables", plan.recheck.variablesChecked},
                    {"holds", plan.recheck.holds()},
                    {"violations", plan.recheck.violations}};
  ordered constraints = ordered::array();
  for (const auto& s : plan.solve.constraints) {
    if (s.evaluations == 0 && s.rejections == 0) continue;
    constraints.push_back({{"name", solver::constraintName(plan.csp, s.ref)},
                           {"declared_at", solver::constraintLocation(plan.csp, s.ref)},
                           {"rejected", s.rejections},
                           {"evaluated", s.evaluations}});
  }
  j["constraints"] = std::move(constraints);
  ordered personal = ordered::array();
  if (plan.ok) {
    for (const auto& e : solver::explainPersonal(plan.csp, plan.solve.assignment)) {
      ordered text = ordered::array();
      for (const auto& t : e.text)
        text.push_back({{"factor", t.factor}, {"subject", t.subject}, {"context", t.context}, {"theta", t.theta}});
      personal.push_back({{"instance", e.name},
                          {"key", e.key},
                          {"applies", e.applies},
                          {"holds", e.holds},
                          {"p", e.probability},
                          {"accept", e.accept},
                          {"entropy_bits", e.entropyBits},
                          {"evidence", e.evidence},
                          {"reached", e.reached},
                          {"in_csp", e.inCsp},
                          {"text", std::move(text)}});
    }
  }
  j["personal"] = std::move(personal);
  ordered observed = ordered::object();
  for (const auto& [name, slot] : program.observationSlots())
    if (slot.offset + slot.type.width <= observation.size())
      observed[name] = valueJson(program, slot.type, observation.data() + slot.offset);
  j["observation"] = std::move(observed);
  return j.dump(2);
}

}  // namespace cbtl::app
