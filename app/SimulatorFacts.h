// SimulatorFacts.h — the facts a domain simulator takes from a loaded program (domains/ProgramFacts.h): the
// scene of its `world` line, already loaded (the one the world built-ins read, so one load per process), and
// its item sets.
#pragma once

#include "app/LoadedProgram.h"
#include "domains/ProgramFacts.h"

namespace cbtl::app {

// Empty facts when the program did not load (ok() false).
domains::ProgramFacts simulatorFacts(const LoadedProgram& program);

}  // namespace cbtl::app
