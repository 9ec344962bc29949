#include "ir/ReadSet.h"

#include <string>

namespace cbtl::ir {
namespace {

void walk(const ConstraintGraph& graph, const Expr& e, std::set<VarId>& out, std::set<std::string>& entered) {
  if (e.op == Op::Var && e.id >= 0) out.insert(static_cast<VarId>(e.id));
  for (VarId v : e.vars) out.insert(v);
  if (e.op == Op::Call && entered.insert(e.text).second) {
    for (const auto& f : graph.functions) {
      if (f.name == e.text && !f.isExtern && f.body) walk(graph, *f.body, out, entered);
    }
  }
  for (const auto& c : e.children) walk(graph, c, out, entered);
}

}  // namespace

void collectReadVars(const ConstraintGraph& graph, const Expr& e, std::set<VarId>& out) {
  std::set<std::string> entered;
  walk(graph, e, out, entered);
}

}  // namespace cbtl::ir
