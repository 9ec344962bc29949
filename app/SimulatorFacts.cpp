#include "app/SimulatorFacts.h"

namespace cbtl::app {

domains::ProgramFacts simulatorFacts(const LoadedProgram& program) {
  domains::ProgramFacts facts;
  if (!program.ok()) return facts;
  facts.scenePath = program.worldPath();
  facts.scene = program.scene();
  facts.clearances = program.graph().clearances;
  facts.itemSets = program.graph().itemSets;
  for (const ir::Constant& c : program.graph().constants) {
    if (!c.indexSet.empty()) continue;
    const ir::Expr& v = c.value;
    if (v.op == ir::Op::Num) facts.numbers[c.name] = {v.number, c.span};
    if (v.op == ir::Op::Neg && v.children.size() == 1 && v.children[0].op == ir::Op::Num)
      facts.numbers[c.name] = {-v.children[0].number, c.span};
  }
  return facts;
}

}  // namespace cbtl::app
