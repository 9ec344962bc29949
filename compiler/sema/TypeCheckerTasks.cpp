// check-types: skills and tasks. A skill's body and action block; a task's body and its skill instances,
// whose arguments are variables of the skills' parameter types and whose instance names are unique.
#include "compiler/sema/TypeCheckerInternal.h"

#include <fmt/format.h>

#include <map>

namespace cbtl::detail {

void TypeChecker::checkSkill(SkillDecl& s) {
  for (auto& b : s.body) checkScopeStmt(*b);
  checkActions(s.actions);
}

void TypeChecker::checkActions(std::vector<std::unique_ptr<ActionStmt>>& stmts) {
  for (auto& s : stmts) {
    switch (s->kind) {
      case ActionStmtKind::Call:
        if (s->calleeRef.kind == RefKind::Action) {
          checkCallable(static_cast<const CallableDecl&>(*s->calleeRef.decl), s->args, s->range);
        } else {
          for (auto& a : s->args) check(a.value.get());
        }
        break;
      case ActionStmtKind::For:
        bindBinder(*s->forBinder, "a 'for' domain");
        checkActions(s->body);
        break;
      case ActionStmtKind::If:
        expect(s->condition.get(), types_.boolean(), "an 'if' condition");
        checkActions(s->body);
        checkActions(s->elseBody);
        break;
      case ActionStmtKind::Block:
        checkActions(s->body);
        break;
      case ActionStmtKind::Allow:
        checkAllow(*s);
        checkActions(s->body);
        break;
    }
  }
}

void TypeChecker::checkTask(TaskDecl& t) {
  for (auto& d : t.body) checkScopeStmt(*d);
  std::map<std::string, SourceRange> names;
  for (auto& inst : t.instances) {
    for (auto& a : inst.args) check(a.value.get());
    const std::string& instName = inst.instanceName();
    if (auto it = names.find(instName); it != names.end()) {
      if (inst.alias.name.empty()) {
        diags_
            .error("E0501", inst.range, fmt::format("skill '{}' runs twice in task '{}'", inst.skill.name, t.name.name))
            .help(fmt::format("name this instance: {} as {}2", inst.skill.name, inst.skill.name))
            .note("first run here", it->second);
      } else {
        diags_
            .error("E0504", inst.alias.range,
                   fmt::format("instance name '{}' is used twice in task '{}'", instName, t.name.name))
            .note("first used here", it->second);
      }
      continue;
    }
    names.emplace(instName, inst.range);
    if (inst.skillDecl != nullptr) checkSkillArgs(inst);
  }
}

void TypeChecker::checkSkillArgs(SkillInstance& inst) {
  const auto& params = inst.skillDecl->params;
  if (inst.args.size() != params.size()) {
    diags_
        .error("E0502", inst.range,
               fmt::format("skill '{}' takes {} argument{}, but {} {} given", inst.skill.name, params.size(),
                           params.size() == 1 ? "" : "s", inst.args.size(), inst.args.size() == 1 ? "is" : "are"))
        .note("declared here", inst.skillDecl->name.range);
    return;
  }
  for (std::size_t i = 0; i < params.size(); ++i) {
    Arg& a = inst.args[i];
    const bool isVar =
        a.value->kind == ExprKind::Name && a.value->ref.kind == RefKind::Variable && !isFamily(a.value->ref.decl);
    const bool isMember = a.value->kind == ExprKind::Index && a.value->operands[0]->kind == ExprKind::Name &&
                          a.value->operands[0]->ref.kind == RefKind::Variable;
    if (!isVar && !isMember) {
      diags_
          .error("E0502", a.range,
                 fmt::format("argument '{}' of skill '{}' must be a variable", params[i].name.name, inst.skill.name))
          .help("skill parameters share a task variable with the skill; declare one with 'var'");
      continue;
    }
    if (params[i].type.resolved && a.value->type && !a.value->type->isError() &&
        params[i].type.resolved != a.value->type) {
      diags_.error("E0502", a.range,
                   fmt::format("argument '{}' of skill '{}' must be {}, but this variable is {}", params[i].name.name,
                               inst.skill.name, params[i].type.resolved->spelling, a.value->type->spelling));
    }
  }
}

}  // namespace cbtl::detail
