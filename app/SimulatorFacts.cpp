#include "app/SimulatorFacts.h"

namespace cbtl::app {

domains::ProgramFacts simulatorFacts(const LoadedProgram& program) {
  domains::ProgramFacts facts;
  if (!program.ok()) return facts;
  facts.scenePath = program.worldPath();
  facts.scene = program.scene();
  facts.itemSets = program.graph().itemSets;
  return facts;
}

}  // namespace cbtl::app
