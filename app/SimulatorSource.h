// SimulatorSource.h — which simulator a loaded program runs against, and making it: an external program (the
// `--simulator CMD` option, or the program's `simulator "CMD";` line) spoken to over the external simulator
// protocol (runtime/sim/ExternalSimulator.h), else the in-process domain of the program's `domain` name
// (domains/DomainRegistry.h).
//
// A `simulator` line's command runs in the folder of the file the program was loaded from, so that
// `simulator "python3 coffee_sim.py";` works from anywhere; a --simulator command runs in the current folder, as
// any command typed there would.
#pragma once

#include "app/LoadedProgram.h"
#include "runtime/approach/Experiment.h"
#include "runtime/sim/ExternalSimulator.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace cbtl::app {

// The external simulator for `program`: `commandLine` when it is not empty, else the program's `simulator` line;
// nullopt when there is neither. Every answer is awaited at most `timeoutMs`.
std::optional<sim::ExternalSimulatorConfig> externalSimulator(const LoadedProgram& program,
                                                              const std::string& commandLine, int timeoutMs);

// A new simulator for `program`, reset with `seed`: the external one when `external` is set (throws
// sim::ExternalSimulatorError when it cannot be started or does not fit the program, and for a program with a
// robot scene, whose state the protocol cannot carry), else the in-process domain of the program's name; nullptr
// when there is no such domain.
std::unique_ptr<sim::DomainSimulator> createSimulator(const LoadedProgram& program,
                                                      const std::optional<sim::ExternalSimulatorConfig>& external,
                                                      const sim::SimulatorOptions& options, std::uint64_t seed);

// The same as a factory; the program's facts and schema are computed once and shared by every simulator it makes.
approach::SimulatorFactory simulatorFactory(const LoadedProgram& program,
                                            const std::optional<sim::ExternalSimulatorConfig>& external);

}  // namespace cbtl::app
