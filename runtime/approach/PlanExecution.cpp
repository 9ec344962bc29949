#include "runtime/approach/PlanExecution.h"

#include "runtime/approach/PreparedProgram.h"

#include <algorithm>

namespace cbtl::approach {

PlanExecution::PlanExecution(const rt::Program& program, const TaskActions& actions, sim::ExecutionModel& model)
    : program_(program), actions_(actions), model_(model) {}

void PlanExecution::unroll(const rt::EvalContext& ctx) {
  calls_.clear();
  stageStart_.assign(1, 0);
  effectFailure_.reset();
  definedStages_ = 0;
  for (std::size_t k = 0; k < actions_.stageCount(); ++k) {
    if (k == 0) {
      model_.enterStage({});
    } else {
      sim::PlanVerdict v = model_.enterStage(calls_);
      if (!v.executes) {
        effectFailure_ = std::move(v);
        break;
      }
    }
    ++definedStages_;
    if (recentPrefix_.size() < actions_.stageCount()) recentPrefix_.resize(actions_.stageCount());
    recentPrefix_[k] = calls_;
    actions_.unrollStage(program_, k, ctx.assignment, ctx.observation, calls_);
    stageStart_.push_back(calls_.size());
  }
  stageStart_.resize(actions_.stageCount() + 1, calls_.size());
  model_.enterStage({});
  unrolled_ = true;
}

bool PlanExecution::enterStage(std::size_t stage, const rt::EvalContext& ctx) {
  if (stage == 0) {
    model_.enterStage({});
    return true;
  }
  if (!unrolled_) unroll(ctx);
  if (stage >= definedStages_) {
    model_.enterStage({});
    return false;
  }
  const std::span<const sim::ActionCall> prefix(calls_.data(), stageStart_[stage]);
  return model_.enterStage(prefix).executes;
}

void PlanExecution::enterRecentStage(std::size_t stage) {
  if (stage == 0 || stage >= recentPrefix_.size()) {
    model_.enterStage({});
    return;
  }
  model_.enterStage(recentPrefix_[stage]);
}

sim::PlanVerdict PlanExecution::check(const rt::EvalContext& ctx) {
  if (!unrolled_) unroll(ctx);
  if (effectFailure_) return *effectFailure_;
  return model_.dryRun(calls_, motionIterations_);
}

std::vector<sim::ActionCall> PlanExecution::calls(const rt::EvalContext& ctx) {
  unroll(ctx);
  return calls_;
}

std::unique_ptr<PlanExecution> makePlanExecution(const PreparedProgram& lp, std::size_t task) {
  rt::BuiltinHost* host = lp.program().host();
  sim::ExecutionModel* model = host != nullptr ? host->executionModel() : nullptr;
  if (model == nullptr) return nullptr;
  const TaskActions& actions = lp.actions(task);
  if (actions.stageCount() == 0) return nullptr;
  for (const std::string& name : actions.actionNames()) {
    if (!model->models(name)) return nullptr;
  }
  return std::make_unique<PlanExecution>(lp.program(), actions, *model);
}

void attachPlan(solver::Csp& csp, PlanExecution& plan, const TaskActions& actions) {
  const rt::Program& program = *csp.program;
  csp.plan = &plan;
  // The stage whose state each entry is evaluated in (kAnyStage when it reads nothing of the world), and the
  // stage it belongs to, which orders the checks.
  std::vector<std::uint32_t> declared;
  csp.constraintStage.clear();
  csp.instanceStage.clear();
  std::vector<std::uint32_t> instanceDeclared;
  for (const rt::PersonalInstance& inst : *csp.instances) {
    std::uint32_t stage = 0;
    for (ir::VarId v : inst.hyperedge) stage = std::max(stage, actions.variableStage(v));
    bool world = inst.guard && program.readsWorld(*inst.guard);
    for (std::uint32_t f : inst.features) world = world || (f != UINT32_MAX && program.readsWorld(f));
    for (const rt::ModelKeyPart& k : inst.key) world = world || (k.fromValue && program.readsWorld(k.node));
    instanceDeclared.push_back(stage);
    csp.instanceStage.push_back(world ? stage : solver::kAnyStage);
  }
  for (const solver::ConstraintRef& c : csp.constraints) {
    if (c.personal()) {
      declared.push_back(instanceDeclared[c.index]);
      csp.constraintStage.push_back(csp.instanceStage[c.index]);
    } else {
      const std::uint32_t stage = actions.constraintStage(c.index);
      declared.push_back(stage);
      csp.constraintStage.push_back(program.readsWorld(program.constraints()[c.index].root) ? stage
                                                                                            : solver::kAnyStage);
    }
  }
  // Stage by stage (personalized first within a stage, as makeCsp orders them): a later stage's state is only
  // computed for candidates whose earlier stages hold.
  std::vector<std::size_t> order(csp.constraints.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return declared[a] < declared[b]; });
  std::vector<solver::ConstraintRef> constraints;
  std::vector<std::uint32_t> stages;
  for (std::size_t i : order) {
    constraints.push_back(csp.constraints[i]);
    stages.push_back(csp.constraintStage[i]);
  }
  csp.constraints = std::move(constraints);
  csp.constraintStage = std::move(stages);
  csp.samplerStage.clear();
  for (std::uint32_t s : csp.samplers)
    csp.samplerStage.push_back(program.samplerReadsWorld(s) ? actions.samplerStage(s) : solver::kAnyStage);
  csp.constraints.push_back(
      {solver::ConstraintKind::PlanExecutes, 0, (std::uint64_t{1} << 62) | (std::uint64_t{csp.taskIndex} << 32)});
  csp.constraintStage.push_back(solver::kAnyStage);
}

OwnedContext::OwnedContext(const rt::Program& program, const std::vector<double>& assignment,
                           const std::vector<double>& observation)
    : x(assignment), obs(observation), frame(std::max<std::size_t>(program.frameSize(), 1) + 1, 0.0) {
  x.resize(std::max<std::size_t>(program.assignmentWidth(), 1), 0.0);
  obs.resize(std::max<std::size_t>(program.observationWidth(), 1), 0.0);
  ctx = rt::EvalContext{x.data(), obs.data(), frame.data(), program.callContext()};
}

}  // namespace cbtl::approach
