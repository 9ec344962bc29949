#include "runtime/core/Personalization.h"

#include "runtime/core/ProgramCompiler.h"
#include "runtime/core/TextContext.h"

#include "ir/Pattern.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <regex>

namespace cbtl::rt {

namespace {

struct ParamMatcher {
  std::vector<GlobPattern> globs;
  std::vector<std::regex> regexes;
};

}  // namespace

std::vector<PersonalInstance> personalize(Program& program, const ir::Task& task) {
  const auto& graph = program.graph();
  std::vector<PersonalInstance> out;
  for (std::size_t gi = 0; gi < graph.generators.size(); ++gi) {
    const ir::Generator& g = graph.generators[gi];
    const std::size_t arity = g.params.size();
    std::vector<ParamMatcher> matchers(arity);
    for (const auto& p : g.patterns) {
      if (p.paramIndex >= arity) continue;
      std::string error;
      std::size_t at = 0;
      if (p.kind == ir::PatternKind::Regex) {
        auto re = compileRegex(p.text, error);
        if (!re) throw RuntimeError(Program::where(p.span), "bad pattern: " + error);
        matchers[p.paramIndex].regexes.push_back(*re);
      } else {
        auto glob = parseGlob(p.text, error, at);
        if (!glob) throw RuntimeError(Program::where(p.span), "bad pattern: " + error);
        matchers[p.paramIndex].globs.push_back(*glob);
      }
    }
    // Candidates per parameter: variables of the task with the parameter's type.
    std::vector<std::vector<ir::VarId>> candidates(arity);
    for (std::size_t i = 0; i < arity; ++i) {
      for (ir::VarId v : task.vars) {
        if (graph.variables.at(v).type.spelling == g.params[i].type.spelling) candidates[i].push_back(v);
      }
    }
    std::vector<ir::VarId> chosen(arity);
    std::map<std::string, std::string> bindings;
    std::function<void(std::size_t)> extend = [&](std::size_t i) {
      if (i == arity) {
        PersonalInstance inst;
        inst.generator = static_cast<std::uint32_t>(gi);
        inst.vars = chosen;
        inst.hyperedge = chosen;
        std::sort(inst.hyperedge.begin(), inst.hyperedge.end());
        inst.hyperedge.erase(std::unique(inst.hyperedge.begin(), inst.hyperedge.end()), inst.hyperedge.end());
        inst.name = g.name + "(";
        for (std::size_t k = 0; k < arity; ++k) inst.name += (k ? ", " : "") + graph.variables.at(chosen[k]).name;
        inst.name += ")";
        for (const auto& c : g.captures) inst.captures.push_back(bindings.count(c) ? bindings.at(c) : "");
        out.push_back(std::move(inst));
        return;
      }
      for (ir::VarId v : candidates[i]) {
        if (std::find(chosen.begin(), chosen.begin() + static_cast<long>(i), v) !=
            chosen.begin() + static_cast<long>(i))
          continue;
        const std::string& name = graph.variables.at(v).name;
        auto saved = bindings;
        bool ok = true;
        for (const auto& glob : matchers[i].globs) ok = ok && matchGlob(glob, name, bindings);
        for (const auto& re : matchers[i].regexes) ok = ok && std::regex_match(name, re);
        if (ok) {
          chosen[i] = v;
          extend(i + 1);
        }
        bindings = std::move(saved);
      }
    };
    if (arity > 0) extend(0);
  }
  // Compile each instance's guard, features and model key against its own variables.
  ProgramCompiler compiler(program);
  for (auto& inst : out) {
    const ir::Generator& g = graph.generators[inst.generator];
    ProgramCompiler::Scope scope;
    std::uint32_t top = 0;
    scope.frameTop = &top;
    for (std::size_t k = 0; k < inst.vars.size(); ++k) {
      ir::Expr read;
      read.op = ir::Op::Var;
      read.id = inst.vars[k];
      read.type = graph.variables.at(inst.vars[k]).type;
      read.text = graph.variables.at(inst.vars[k]).name;
      scope.params.push_back(compiler.compile(read, scope));
    }
    if (g.guard) inst.guard = compiler.compile(*g.guard, scope);
    for (const auto& f : g.factors) {
      inst.features.push_back(f.feature ? compiler.compile(*f.feature, scope) : UINT32_MAX);
      inst.featureTypes.push_back(f.feature ? program.typeOf(f.feature->type) : ValueType{});
      inst.contexts.push_back(compileContext(compiler, program, f, scope));
    }
    for (const auto& perKey : g.perKeys) {
      const std::string& keyName = perKey.name;
      ModelKeyPart part;
      bool found = false;
      if (perKey.expr) {  // an expression over the parameters (and observations), evaluated like a feature
        part.fromValue = true;
        part.node = compiler.compile(*perKey.expr, scope);
        part.type = program.typeOf(perKey.expr->type);
        found = true;
      }
      for (std::size_t k = 0; !found && k < g.params.size(); ++k) {
        if (g.params[k].name == keyName) {
          part.fromValue = true;
          part.node = scope.params[k];
          part.type = program.typeOf(g.params[k].type);
          found = true;
        }
      }
      for (std::size_t c = 0; !found && c < g.captures.size(); ++c) {
        if (g.captures[c] == keyName) {
          part.text = inst.captures[c];
          found = true;
        }
      }
      if (!found)
        throw RuntimeError(Program::where(g.span),
                           fmt::format("'per {}' names neither a parameter nor a capture", keyName));
      inst.key.push_back(std::move(part));
    }
  }
  return out;
}

}  // namespace cbtl::rt
