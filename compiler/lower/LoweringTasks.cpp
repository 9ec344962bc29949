// lower: tasks. A task's graph is the global declarations, then its own body, then each skill instance's
// body with the instance's variables renamed "<instance>.<var>" and its parameters replaced by the
// task's arguments; the instance's actions are lowered in the same context.
#include "compiler/lower/LoweringInternal.h"

#include <fmt/format.h>

namespace cbtl::detail {
namespace {

std::vector<const Decl*> raw(const std::vector<std::unique_ptr<Decl>>& body) {
  std::vector<const Decl*> out;
  for (const auto& d : body) out.push_back(d.get());
  return out;
}

}  // namespace

void Lowerer::lowerTask(const TaskDecl& t, std::set<std::string>& usedSkills) {
  ir::Task task;
  task.name = t.name.name;
  task.span = span(t.range);
  task.vars = globalVars_;
  task.constraints = globalConstraints_;
  task.samplers = globalSamplers_;
  task.costs = globalCosts_;
  Ctx ctx;
  ctx.scope = "task:" + t.name.name;
  lowerBody(raw(t.body), ctx, task.vars, task.constraints, task.samplers, task.costs);
  for (const auto& inst : t.instances) {
    if (tooLarge_) break;
    if (inst.skillDecl == nullptr) continue;
    usedSkills.insert(inst.skill.name);
    lowerSkillInstance(t, inst, ctx, task);
  }
  g_.tasks.push_back(std::move(task));
}

void Lowerer::lowerSkillInstance(const TaskDecl& t, const SkillInstance& inst, Ctx& ctx, ir::Task& task) {
  ir::SkillInstance si;
  si.skill = inst.skill.name;
  si.name = inst.instanceName();
  si.span = span(inst.range);
  Ctx sctx;
  sctx.scope = fmt::format("skill:{}/{}", t.name.name, si.name);
  sctx.prefix = si.name + ".";
  sctx.skill = inst.skillDecl;
  // Arguments are lowered in the task's context: they name the task's variables.
  for (const auto& a : inst.args) {
    ir::Expr x = lower(a.value.get(), ctx);
    if (x.op == ir::Op::Var) si.params.push_back(static_cast<ir::VarId>(x.id));
    sctx.skillParams.push_back(std::move(x));
  }
  std::vector<ir::VarId> vars;
  std::vector<std::uint32_t> constraints, samplers, costs;
  lowerBody(raw(inst.skillDecl->body), sctx, vars, constraints, samplers, costs);
  for (const auto& a : inst.skillDecl->actions) {
    si.actions.push_back(lowerAction(*a, sctx));
    grow(actionSize(si.actions.back()), a->range);
  }
  task.vars.insert(task.vars.end(), vars.begin(), vars.end());
  task.constraints.insert(task.constraints.end(), constraints.begin(), constraints.end());
  task.samplers.insert(task.samplers.end(), samplers.begin(), samplers.end());
  task.costs.insert(task.costs.end(), costs.begin(), costs.end());
  si.vars = std::move(vars);
  si.constraints = std::move(constraints);
  si.samplers = std::move(samplers);
  task.instances.push_back(std::move(si));
}

ir::Action Lowerer::lowerAction(const ActionStmt& s, Ctx& ctx) {
  ir::Action a;
  a.span = span(s.range);
  switch (s.kind) {
    case ActionStmtKind::Call: {
      a.kind = ir::ActionKind::Call;
      a.name = s.callee.name;
      const auto* callee =
          s.calleeRef.kind == RefKind::Action ? static_cast<const CallableDecl*>(s.calleeRef.decl) : nullptr;
      for (const auto* arg : orderedArgs(callee, s.args)) a.args.push_back(lower(arg->value.get(), ctx));
      break;
    }
    case ActionStmtKind::For:
      a.kind = ir::ActionKind::For;
      for (const auto& n : s.forBinder->names) a.binders.push_back(n->name.name);
      a.set = lower(s.forBinder->set.get(), ctx);
      for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
      break;
    case ActionStmtKind::If:
      a.kind = ir::ActionKind::If;
      a.condition = lower(s.condition.get(), ctx);
      for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
      for (const auto& b : s.elseBody) a.elseBody.push_back(lowerAction(*b, ctx));
      break;
    case ActionStmtKind::Block:
      a.kind = ir::ActionKind::Block;
      for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
      break;
    case ActionStmtKind::Allow:
      a.kind = ir::ActionKind::Allow;
      a.allow = lowerAllowance(*s.allow, ctx);
      for (const auto& b : s.body) a.body.push_back(lowerAction(*b, ctx));
      break;
  }
  return a;
}

ir::Allowance Lowerer::lowerAllowance(const AllowClause& a, Ctx& ctx) {
  ir::Allowance out;
  out.part = a.part.name == "robot"     ? ir::AllowPart::Robot
             : a.part.name == "gripper" ? ir::AllowPart::Gripper
                                        : ir::AllowPart::Held;
  if (a.clearance != nullptr)
    out.clearance = a.clearance->name.name;
  else
    out.target = lower(a.target.get(), ctx);
  const double distance = metres(a.length);
  // `touch` lets the part sink in by the distance: a negative separation (touching with no depth is separation 0).
  out.separation = a.mode.name == "touch" && distance > 0 ? -distance : distance;
  return out;
}

}  // namespace cbtl::detail
