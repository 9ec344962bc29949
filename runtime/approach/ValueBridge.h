// ValueBridge.h — converting between the runtime's flat values and the simulator boundary's values
// (sim::Value: numbers, vectors, and enum members / items / texts by name).
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <string>
#include <vector>

namespace cbtl::approach {

sim::Value toSimValue(const rt::Program& program, const rt::ValueType& type, const double* v);

// Writes `value` as `type` into out[0 .. width). Returns false (and sets `error`) when it does not fit.
bool fromSimValue(const rt::Program& program, const rt::ValueType& type, const sim::Value& value, double* out,
                  std::string& error);

// The observation vector laid out as program.observationSlots(); throws rt::RuntimeError naming a missing
// or ill-typed observation.
std::vector<double> observationVector(const rt::Program& program, const sim::Observation& observation);

}  // namespace cbtl::approach
