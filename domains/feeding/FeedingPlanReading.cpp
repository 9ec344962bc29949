#include "domains/feeding/FeedingPlanReading.h"

#include "runtime/approach/ValueBridge.h"

#include <stdexcept>

namespace cbtl::domains::feeding {

std::optional<sim::Value> readVariable(const approach::PreparedProgram& lp, std::size_t task,
                                       const std::vector<double>& assignment, const std::string& name) {
  const auto& graph = lp.graph();
  const auto& program = lp.program();
  for (ir::VarId v : graph.tasks.at(task).vars) {
    if (graph.variables[v].name != name) continue;
    const auto& slot = program.slot(v);
    if (assignment.size() < slot.offset + slot.type.width) return std::nullopt;
    return approach::toSimValue(program, slot.type, assignment.data() + slot.offset);
  }
  return std::nullopt;
}

std::optional<world::ArmConfig> readConf(const approach::PreparedProgram& lp, std::size_t task,
                                         const std::vector<double>& assignment, const std::string& name) {
  const auto v = readVariable(lp, task, assignment, name);
  if (!v || v->kind != sim::Value::Kind::Vector || v->vector.size() != world::ArmConfig{}.size()) return std::nullopt;
  world::ArmConfig q{};
  std::copy(v->vector.begin(), v->vector.end(), q.begin());
  return q;
}

PlanChoices readPlanChoices(const approach::PreparedProgram& lp, std::size_t task,
                            const std::vector<double>& assignment) {
  PlanChoices c;
  const auto text = [&](const char* name) {
    const auto v = readVariable(lp, task, assignment, name);
    return v && v->kind == sim::Value::Kind::Name ? v->text : std::string();
  };
  const auto xy = [&](const char* name) -> std::optional<std::vector<double>> {
    const auto v = readVariable(lp, task, assignment, name);
    if (!v || v->kind != sim::Value::Kind::Vector || v->vector.size() != 2) return std::nullopt;
    return v->vector;
  };
  c.plate = xy("platePos");
  c.drink = xy("drinkPos");
  c.dip = text("acquireBite.dip");
  c.signal = text("transferBite.readySignal");
  c.verbosity = text("transferBite.verbosity");
  c.abovePlateConf = readConf(lp, task, assignment, kAbovePlateConf);
  c.drinkConf = readConf(lp, task, assignment, kDrinkConf);
  return c;
}

PlanRun runPlan(FeedingSimulator& world, const std::vector<sim::ActionCall>& calls, const FeedbackHandler& onFeedback) {
  PlanRun run;
  for (const auto& call : calls) {
    sim::StepResult r = world.act(call);
    if (r.status == sim::ActionStatus::UnknownAction)
      throw std::runtime_error("the Feeding simulator rejected action '" + call.name + "': " + r.message);
    if (onFeedback && !r.feedback.empty()) onFeedback(r.feedback);
    for (auto& f : r.feedback) {
      if (f.name == "viewBlocked") ++run.complaints;
      run.feedback.push_back(std::move(f));
    }
    for (auto& p : r.preferences) run.preferences.push_back(std::move(p));
    for (auto& m : r.measures) run.measures.push_back(std::move(m));
    run.failed = run.failed || r.taskFailed;
    if (r.taskDone) {
      run.done = true;
      break;
    }
  }
  return run;
}

}  // namespace cbtl::domains::feeding
