#include "runtime/solver/Csp.h"

#include <algorithm>

namespace cbtl::solver {

Csp makeCsp(const rt::Program& program, std::uint32_t taskIndex, const std::vector<rt::PersonalInstance>& instances,
            const model::UserModel& user, std::vector<double> observation, PersonalMode personal, CostKind cost) {
  Csp csp;
  csp.program = &program;
  csp.task = &program.graph().tasks.at(taskIndex);
  csp.taskIndex = taskIndex;
  csp.instances = &instances;
  csp.user = &user;
  // Every evaluation reads the observation by the program's offsets: a short vector reads as zeros.
  observation.resize(std::max<std::size_t>(program.observationWidth(), 1), 0.0);
  csp.initial = program.initialAssignment(observation);
  csp.observation = std::move(observation);
  csp.cost = cost;
  // Personalized constraints first: they are cheap and reject most candidates once learned.
  if (personal == PersonalMode::Include) {
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      csp.constraints.push_back(
          {ConstraintKind::Personal, i, (std::uint64_t{1} << 63) | (std::uint64_t{taskIndex} << 32) | i});
    }
  }
  // CBTL's exploration keeps the constraints of generators that explore only where they accept.
  if (personal == PersonalMode::Exclude && cost == CostKind::Entropy) {
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      if (!program.graph().generators.at(instances[i].generator).exploreAccepted) continue;
      csp.constraints.push_back(
          {ConstraintKind::Personal, i, (std::uint64_t{1} << 63) | (std::uint64_t{taskIndex} << 32) | i});
    }
  }
  for (std::uint32_t c : csp.task->constraints) csp.constraints.push_back({ConstraintKind::Hard, c, c});
  // Exploiting without a declared cost, the robot does what the user most likely welcomes: among the solutions the
  // personalized constraints accept (P >= accept), the one with the highest P; not merely the first (on a robot the
  // first is often a remembered value at the edge of what the model accepts, right where it is least sure).
  if (cost == CostKind::Declared && csp.task->costs.empty()) {
    csp.cost = personal == PersonalMode::Include && !instances.empty() ? CostKind::Likelihood : CostKind::None;
  }
  if (csp.cost == CostKind::Entropy || csp.cost == CostKind::Likelihood) {
    for (std::uint32_t i = 0; i < instances.size(); ++i) csp.scoredInstances.push_back(i);
  }
  csp.samplers = csp.task->samplers;
  return csp;
}

std::string constraintName(const Csp& csp, const ConstraintRef& c) {
  if (c.kind == ConstraintKind::PlanExecutes) return kPlanExecutesName;
  if (c.personal()) return (*csp.instances)[c.index].name;
  return csp.program->graph().constraints.at(c.index).name;
}

std::string constraintLocation(const Csp& csp, const ConstraintRef& c) {
  if (c.kind == ConstraintKind::PlanExecutes) return rt::Program::where(csp.task->span);
  if (c.personal()) {
    const auto& inst = (*csp.instances)[c.index];
    return rt::Program::where(csp.program->graph().generators.at(inst.generator).span);
  }
  return rt::Program::where(csp.program->graph().constraints.at(c.index).span);
}

}  // namespace cbtl::solver
