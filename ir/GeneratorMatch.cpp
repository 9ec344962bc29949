#include "ir/GeneratorMatch.h"

#include "ir/Pattern.h"

#include <map>
#include <optional>
#include <regex>
#include <string>

namespace cbtl::ir {

std::set<VarId> variablesMatchedBy(const ConstraintGraph& graph, const Generator& gen,
                                   const std::vector<VarId>& candidates) {
  std::set<VarId> out;
  for (std::size_t i = 0; i < gen.params.size(); ++i) {
    const Pattern* pattern = nullptr;
    for (const auto& p : gen.patterns)
      if (p.paramIndex == i) pattern = &p;
    std::optional<GlobPattern> glob;
    std::optional<std::regex> regex;
    std::string error;
    std::size_t at = 0;
    if (pattern != nullptr && pattern->kind == PatternKind::Glob) glob = parseGlob(pattern->text, error, at);
    if (pattern != nullptr && pattern->kind == PatternKind::Regex) regex = compileRegex(pattern->text, error);
    for (VarId id : candidates) {
      const Variable& v = graph.variables.at(id);
      if (v.type.spelling != gen.params[i].type.spelling) continue;
      std::map<std::string, std::string> bindings;
      if (pattern == nullptr || (glob && matchGlob(*glob, v.name, bindings)) ||
          (regex && std::regex_match(v.name, *regex)))
        out.insert(id);
    }
  }
  return out;
}

}  // namespace cbtl::ir
