// DomainRegistry.h — creates a domain's simulator by the domain's name (the `domain` line of its .cbtl file).
//
// Only the domains whose library was built are known; the build links every domains/<name>/ folder that has a
// CMakeLists.txt. The registry owns nothing: each call makes a new, independent simulator.
#pragma once

#include "runtime/sim/DomainSimulator.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::domains {

// A new simulator for `domain` (e.g. "cooking"), constructed with `options` and reset with `seed`; nullptr when
// no simulator of that name was built. Throws what the domain's constructor throws for invalid options.
std::unique_ptr<cbtl::sim::DomainSimulator> createSimulator(const std::string& domain,
                                                            const cbtl::sim::SimulatorOptions& options,
                                                            std::uint64_t seed);

// The names createSimulator accepts, sorted.
std::vector<std::string> knownDomains();

}  // namespace cbtl::domains
