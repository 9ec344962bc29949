// `:eval EXPR` — an expression of the language evaluated against the session's current assignment, as a GHCi or
// utop user expects. The expression is compiled by the real compiler in the scope of the task last solved (its
// variables, the program's constants, observations and functions): the program's own text is compiled again with
// one extra `require` in that task's body, `(EXPR) == (EXPR)`, which type-checks EXPR as any comparable value
// and leaves the layout of every variable unchanged; the left side is then compiled and evaluated alone. Skill
// variables (`acquireBite.dip`) are not names in a task's scope: after a solve, those with scalar values are read
// from the solution and put into the expression as literals (and said so); vectors and configurations are not.
#include "app/PlanReport.h"
#include "app/repl/ReplSession.h"
#include "runtime/core/ProgramCompiler.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace cbtl::app::repl {

namespace {

constexpr const char* kEvalName = "__repl_eval";

// Where the extra require goes: before the closing brace of `task`, or at the end of a file without tasks.
std::size_t insertionPoint(const std::string& text, const ir::Task& task) {
  if (task.implicit || task.span.endLine == 0) return text.size();
  std::size_t lineStart = 0;
  for (std::uint32_t line = 1; line < task.span.endLine && lineStart != std::string::npos; ++line)
    lineStart = text.find('\n', lineStart) + 1;
  if (lineStart == std::string::npos || lineStart > text.size()) return text.size();
  const std::size_t end = std::min(text.size(), lineStart + task.span.endColumn + 1);
  const std::size_t brace = text.rfind('}', end);
  return brace != std::string::npos && brace >= lineStart ? brace : text.size();
}

// Whether every ')' of `expr` closes a '(' of its own (quotes are not looked into: a text holding parentheses only
// costs the friendlier wording below).
bool parenthesesBalance(const std::string& expr) {
  int depth = 0;
  for (char c : expr) {
    depth += c == '(' ? 1 : c == ')' ? -1 : 0;
    if (depth < 0) return false;
  }
  return depth == 0;
}

// The first diagnostic of a failed compile of `expr`, without the location inside the rewritten text.
std::string firstDiagnostic(const std::string& errors, const std::string& expr) {
  std::istringstream in(errors);
  std::string line, message, notes;
  while (std::getline(in, line)) {
    if (message.empty()) {
      const std::size_t at = line.find("error");
      if (at == std::string::npos) continue;
      const std::size_t colon = line.find(": ", at);
      message = colon != std::string::npos ? line.substr(colon + 2) : line.substr(at);
    } else if (line.rfind("  = ", 0) == 0) {
      notes += "\n" + line;
    } else if (line.find("error") != std::string::npos && line.find(": ") != std::string::npos) {
      break;
    }
  }
  const std::size_t at = message.find(" in the constraint");
  if (at != std::string::npos) message.replace(at, 18, " in the expression");
  // The expression is compiled inside parentheses of ours: a `)` the parser did not expect is its end.
  const std::string ours = "found ')' in the expression";
  const std::size_t paren = message.find(ours);
  if (paren != std::string::npos && parenthesesBalance(expr))
    message.replace(paren, ours.size(), "but the expression ends there");
  return message.empty() ? "the expression does not compile" : message + notes;
}

// A value as the REPL reads it back: a text that is not a plain name in quotes (observe, why-not).
std::string pasteable(const rt::Program& program, const rt::ValueType& type, const double* v) {
  std::string text = renderObserved(program, type, v);
  if (type.kind != rt::ValueKind::Text) return text;
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(),
                                                  [](unsigned char c) { return std::isalnum(c) != 0 || c == '_'; });
  return plain ? text : nlohmann::json(text).dump();
}

bool identifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// A skill's variable (`acquireBite.dip`) is no name in the task's scope, so `:eval` reads it from the solution: every
// whole-word occurrence of one whose value is a scalar literal (bool, number, enum member, item, text) is replaced by
// that literal. Returns the rewritten expression and "name = value" for each one replaced.
std::pair<std::string, std::vector<std::string>> withSkillValues(const std::string& expr, const rt::Program& program,
                                                                 const std::vector<double>& assignment) {
  std::vector<const ir::Variable*> skillVars;
  for (const auto& v : program.graph().variables)
    if (v.name.find('.') != std::string::npos) skillVars.push_back(&v);
  // Longest first, so that `a.bc` is not cut by `a.b`.
  std::sort(skillVars.begin(), skillVars.end(),
            [](const ir::Variable* a, const ir::Variable* b) { return a->name.size() > b->name.size(); });
  std::string out = expr;
  std::vector<std::string> used;
  for (const ir::Variable* v : skillVars) {
    const rt::VarSlot& slot = program.slot(v->id);
    if (slot.offset + slot.type.width > assignment.size()) continue;
    const double* value = assignment.data() + slot.offset;
    std::string literal;
    switch (slot.type.kind) {
      case rt::ValueKind::Bool:
      case rt::ValueKind::Int:
      case rt::ValueKind::Real:
        literal = program.render(slot.type, value);
        break;
      case rt::ValueKind::Item: {  // entries are named through their set: dips.noDip
        const auto& sets = program.graph().itemSets;
        const auto set = std::find_if(sets.begin(), sets.end(),
                                      [&](const ir::ItemSet& s) { return s.itemType == slot.type.typeName; });
        if (set == sets.end()) continue;
        literal = set->name + "." + program.render(slot.type, value);
        break;
      }
      case rt::ValueKind::Enum:
        literal = slot.type.typeName + "." + program.render(slot.type, value);
        break;
      case rt::ValueKind::Text:
        literal = nlohmann::json(program.render(slot.type, value)).dump();
        break;
      default:
        continue;  // vectors, poses, configurations: `show plan` shows them
    }
    bool replaced = false;
    for (std::size_t at = out.find(v->name); at != std::string::npos; at = out.find(v->name, at)) {
      const std::size_t end = at + v->name.size();
      if ((at > 0 && (identifierChar(out[at - 1]) || out[at - 1] == '.')) ||
          (end < out.size() && identifierChar(out[end]))) {
        at = end;
        continue;
      }
      out.replace(at, v->name.size(), literal);
      at += literal.size();
      replaced = true;
    }
    if (replaced) used.push_back(fmt::format("{} = {}", v->name, program.render(slot.type, value)));
  }
  return {out, used};
}

}  // namespace

bool ReplSession::cmdEval(const std::string& original) {
  if (!requireProgram()) return false;
  if (original.empty()) return fail(":eval EXPR: an expression over the constants, observations and task variables");
  // Skill variables are read from the solution (there is none before a solve: they keep their names and fail).
  const bool haveSolution = plan_ && plan_->ok;
  const auto [expr, skillValues] = haveSolution ? withSkillValues(original, lp_->program(), plan_->solve.assignment)
                                                : std::pair<std::string, std::vector<std::string>>{original, {}};
  std::ifstream in(path_);
  std::stringstream source;
  source << in.rdbuf();
  if (!in || path_.size() < 5 || path_.compare(path_.size() - 5, 5, ".cbtl") != 0)
    return fail(fmt::format(":eval compiles the program's source; '{}' is not a readable .cbtl file", path_));
  const ir::Task& task = plan_ ? *plan_->csp.task : lp_->graph().tasks.front();
  std::string text = source.str();
  text.insert(insertionPoint(text, task), fmt::format("\nrequire {}: ({}) == ({});\n", kEvalName, expr, expr));
  auto probe = LoadedProgram::fromSource(path_, std::move(text), config_.stdlibDir);
  if (!probe->ok()) {
    std::string hint;
    for (const auto& v : lp_->graph().variables)
      if (v.name.find('.') != std::string::npos && expr.find(v.name) != std::string::npos) {
        hint = fmt::format(
            "\n  = note: '{}' is a skill's variable, not a name in the task's scope: show plan "
            "shows its value",
            v.name);
        break;
      }
    return fail(firstDiagnostic(probe->errors(), expr) + hint);
  }
  const auto& constraints = probe->graph().constraints;
  const auto c =
      std::find_if(constraints.begin(), constraints.end(), [](const ir::Constraint& k) { return k.name == kEvalName; });
  rt::Program& program = probe->program();
  if (c == constraints.end() || c->expr.children.size() != 2 ||
      program.assignmentWidth() != lp_->program().assignmentWidth() ||
      program.observationWidth() != lp_->program().observationWidth())
    return fail("internal error: the expression changed the program's layout (this is a bug; please report it)");
  const ir::Expr& lhs = c->expr.children[0];
  rt::ProgramCompiler compiler(program);
  rt::ProgramCompiler::Scope scope;
  std::uint32_t top = 0;
  scope.frameTop = &top;
  const std::uint32_t root = compiler.compile(lhs, scope);

  const bool solved = plan_ && plan_->ok;
  const std::vector<double> observation = solved ? planObservation_ : observation_;
  const std::vector<double> assignment =
      solved ? plan_->solve.assignment : lp_->program().initialAssignment(observation_);
  if (world_) probe->syncWorld(*world_);
  std::vector<double> frame(program.frameSize() + 1, 0.0), value(program.pool().width(root), 0.0);
  rt::EvalContext ctx{assignment.data(), observation.data(), frame.data(), program.callContext()};
  program.pool().eval(root, ctx, value.data());
  fmt::print(out_, "{} : {} = {}{}{}\n", original, lhs.type.spelling,
             pasteable(program, program.typeOf(lhs.type), value.data()),
             solved ? "" : "   (no solution yet: variables at their initial values)",
             skillValues.empty() ? "" : fmt::format("   (from the solution: {})", fmt::join(skillValues, ", ")));
  return true;
}

}  // namespace cbtl::app::repl
