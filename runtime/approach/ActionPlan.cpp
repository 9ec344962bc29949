#include "runtime/approach/ActionPlan.h"

#include "runtime/approach/ValueBridge.h"
#include "runtime/core/ProgramCompiler.h"

#include <fmt/format.h>

#include "ir/ReadSet.h"

#include <algorithm>
#include <set>

namespace cbtl::approach {

namespace {

struct Compiler {
  rt::Program& program;
  rt::ProgramCompiler expressions;
  rt::ProgramCompiler::Scope scope;
  std::uint32_t top = 0;

  void compileAllowance(const ir::Allowance& allow, const std::string& at, CompiledAction& c) {
    static constexpr const char* kParts[] = {"robot", "gripper", "held"};  // ir::AllowPart order
    const auto part = static_cast<std::size_t>(allow.part);
    if (part >= std::size(kParts)) throw rt::RuntimeError(at, "an 'allow' for an unknown part of the robot");
    c.exception.part = kParts[part];
    c.exception.separation = allow.separation;
    c.exception.declaredAt = at;
    if (!allow.clearance.empty()) {
      const ir::Clearance* found = nullptr;
      for (const ir::Clearance& cl : program.graph().clearances)
        if (cl.name == allow.clearance) found = &cl;
      if (found == nullptr) throw rt::RuntimeError(at, fmt::format("no clearance '{}' is declared", allow.clearance));
      c.exception.names = found->bodies;
    } else if (allow.target) {
      c.args.push_back(expressions.compile(*allow.target, scope));
      c.argTypes.push_back(program.typeOf(allow.target->type));
    } else {
      throw rt::RuntimeError(at, "an 'allow' names neither a clearance nor a body");
    }
  }

  CompiledAction compile(const ir::Action& a) {
    CompiledAction c;
    c.kind = a.kind;
    c.name = a.name;
    const std::string at = rt::Program::where(a.span);
    if (a.kind == ir::ActionKind::Call) {
      const ir::Function* f = nullptr;
      for (const auto& fn : program.graph().functions) {
        if (fn.name == a.name) f = &fn;
      }
      if (f == nullptr || f->kind != ir::FunctionKind::Action)
        throw rt::RuntimeError(at, fmt::format("'{}' is not an action", a.name));
      for (std::size_t i = 0; i < a.args.size(); ++i) {
        c.args.push_back(expressions.compile(a.args[i], scope));
        c.argTypes.push_back(program.typeOf(a.args[i].type));
      }
      return c;
    }
    if (a.kind == ir::ActionKind::For) {
      if (a.binders.size() != 1 || !a.set) throw rt::RuntimeError(at, "a 'for' in a skill takes one binder and a set");
      c.binderSlot = top++;
      const ir::Expr& set = *a.set;
      if (set.op == ir::Op::Range) {
        c.lo = expressions.compile(set.children[0], scope);
        c.hi = expressions.compile(set.children[1], scope);
      } else if (set.op == ir::Op::EnumSet) {
        const auto* e = program.findEnum(set.text);
        c.memberCount = e ? static_cast<std::uint32_t>(e->members.size()) : 0;
      } else if (set.op == ir::Op::ItemSet) {
        const auto* s = program.findItemSet(set.text);
        c.memberCount = s ? static_cast<std::uint32_t>(s->entries.size()) : 0;
      } else {
        throw rt::RuntimeError(at, "a 'for' in a skill must range over an enum, an item set or an integer range");
      }
      const auto saved = scope.locals;
      scope.locals[a.binders[0]] = c.binderSlot;
      for (const auto& b : a.body) c.body.push_back(compile(b));
      scope.locals = saved;
      return c;
    }
    if (a.kind == ir::ActionKind::Allow) {
      if (!a.allow) throw rt::RuntimeError(at, "an 'allow' without its exception");
      compileAllowance(*a.allow, at, c);
    }
    if (a.kind == ir::ActionKind::If && a.condition) c.condition = expressions.compile(*a.condition, scope);
    for (const auto& b : a.body) c.body.push_back(compile(b));
    for (const auto& b : a.elseBody) c.elseBody.push_back(compile(b));
    return c;
  }
};

constexpr std::size_t kMaxCalls = 100000;

// `allowed`: the exceptions of the `allow` blocks around `actions`, outermost first.
void run(const rt::Program& program, const std::vector<CompiledAction>& actions, rt::EvalContext& ctx,
         std::vector<sim::ClearanceException>& allowed, std::vector<sim::ActionCall>& out) {
  const auto& pool = program.pool();
  for (const auto& a : actions) {
    if (out.size() >= kMaxCalls) return;
    if (a.kind == ir::ActionKind::Call) {
      sim::ActionCall call;
      call.name = a.name;
      double v[rt::kMaxValueWidth];
      for (std::size_t i = 0; i < a.args.size(); ++i) {
        pool.eval(a.args[i], ctx, v);
        call.args.push_back(toSimValue(program, a.argTypes[i], v));
      }
      call.exceptions = allowed;
      out.push_back(std::move(call));
    } else if (a.kind == ir::ActionKind::Allow) {
      sim::ClearanceException e = a.exception;
      if (!a.args.empty()) {
        double v[rt::kMaxValueWidth];
        pool.eval(a.args[0], ctx, v);
        e.names = {toSimValue(program, a.argTypes[0], v).text};
      }
      allowed.push_back(std::move(e));
      run(program, a.body, ctx, allowed, out);
      allowed.pop_back();
    } else if (a.kind == ir::ActionKind::For) {
      double lo = 0, hi = static_cast<double>(a.memberCount) - 1;
      if (a.lo) {
        lo = pool.evalScalar(*a.lo, ctx);
        hi = pool.evalScalar(*a.hi, ctx);
      }
      // Bounded by count, not by the calls made: a body that emits nothing must not spin over a huge range.
      std::size_t iterations = 0;
      for (double i = lo; i <= hi && out.size() < kMaxCalls && iterations < kMaxCalls; i += 1, ++iterations) {
        ctx.frame[a.binderSlot] = i;
        run(program, a.body, ctx, allowed, out);
      }
    } else if (a.kind == ir::ActionKind::If) {
      run(program, (!a.condition || pool.evalBool(*a.condition, ctx)) ? a.body : a.elseBody, ctx, allowed, out);
    } else {
      run(program, a.body, ctx, allowed, out);
    }
  }
}

// Every variable an action (its arguments, loop sets and conditions, nested actions) reads.
void collectActionReads(const ir::ConstraintGraph& graph, const ir::Action& a, std::set<ir::VarId>& out,
                        std::set<std::string>& names) {
  if (a.kind == ir::ActionKind::Call) names.insert(a.name);
  for (const auto& e : a.args) ir::collectReadVars(graph, e, out);
  if (a.set) ir::collectReadVars(graph, *a.set, out);
  if (a.condition) ir::collectReadVars(graph, *a.condition, out);
  if (a.allow && a.allow->target) ir::collectReadVars(graph, *a.allow->target, out);
  for (const auto& b : a.body) collectActionReads(graph, b, out, names);
  for (const auto& b : a.elseBody) collectActionReads(graph, b, out, names);
}

}  // namespace

TaskActions::TaskActions(rt::Program& program, const ir::Task& task) {
  Compiler c{program, rt::ProgramCompiler(program), {}, 0};
  c.scope.frameTop = &c.top;
  std::set<ir::VarId> reads;
  std::set<std::string> names;
  readsBefore_.emplace_back();
  for (std::uint32_t k = 0; k < task.instances.size(); ++k) {
    const ir::SkillInstance& inst = task.instances[k];
    auto& stage = stages_.emplace_back();
    for (const auto& a : inst.actions) {
      stage.push_back(c.compile(a));
      collectActionReads(program.graph(), a, reads, names);
    }
    readsBefore_.emplace_back(reads.begin(), reads.end());
    for (std::uint32_t con : inst.constraints) constraintStage_[con] = k;
    for (std::uint32_t smp : inst.samplers) samplerStage_[smp] = k;
    for (ir::VarId v : inst.vars) variableStage_[v] = k;
  }
  if (stages_.empty()) readsBefore_.emplace_back();  // reads(): empty
  actionNames_.assign(names.begin(), names.end());
  frameWidth_ = c.top + 1;
}

namespace {
std::uint32_t stageIn(const std::map<std::uint32_t, std::uint32_t>& m, std::uint32_t key) {
  const auto it = m.find(key);
  return it == m.end() ? 0 : it->second;
}
}  // namespace

std::uint32_t TaskActions::constraintStage(std::uint32_t constraint) const {
  return stageIn(constraintStage_, constraint);
}
std::uint32_t TaskActions::samplerStage(std::uint32_t sampler) const { return stageIn(samplerStage_, sampler); }
std::uint32_t TaskActions::variableStage(ir::VarId v) const { return stageIn(variableStage_, v); }

void TaskActions::unrollStage(const rt::Program& program, std::size_t stage, const double* x, const double* obs,
                              std::vector<sim::ActionCall>& out) const {
  std::vector<double> frame(std::max<std::size_t>(frameWidth_, program.frameSize()) + 1, 0.0);
  rt::EvalContext ctx{x, obs, frame.data(), program.callContext()};
  std::vector<sim::ClearanceException> allowed;
  run(program, stages_.at(stage), ctx, allowed, out);
}

std::vector<sim::ActionCall> TaskActions::unroll(const rt::Program& program, const std::vector<double>& solution,
                                                 const std::vector<double>& observation) const {
  std::vector<double> x = solution, obs = observation;
  x.resize(std::max<std::size_t>(program.assignmentWidth(), 1), 0.0);
  obs.resize(std::max<std::size_t>(program.observationWidth(), 1), 0.0);
  std::vector<sim::ActionCall> out;
  for (std::size_t k = 0; k < stages_.size(); ++k) unrollStage(program, k, x.data(), obs.data(), out);
  return out;
}

}  // namespace cbtl::approach
