// ObservationFile.h — observations given as a JSON file (`cbtl solve --observe obs.json`), for programs whose domain
// has no simulator or to describe a situation the simulator would not draw.
//
//   {"foodOnPlate": "frenchFries", "dipsOnTable": ["ketchup", "bbqSauce"], "plateXY": [0.31, 0.30],
//    "stock[salt]": 2.5, "served": true}
//
// Keys are the program's observations (a family's members as "name[member]"); a value is a number, true/false, a
// name (an enum member or item entry, bare or qualified) or text, an array of numbers (vec, SE2, SE3, Conf) or an
// array of names (a set). Each is checked against its declaration. The file's values are written over `base` (the
// simulator's observation; empty without a simulator, when every observation must be given).
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <stdexcept>
#include <string>

namespace cbtl::app {

// Bad input: the file, the JSON Pointer of the offending value and what was expected.
struct ObservationFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The file's entries alone, each checked against its declaration.
sim::Observation readObservationEntries(const std::string& path, const rt::Program& program);

// The file's entries written over `base`; with an empty base every observation must be given.
sim::Observation readObservationFile(const std::string& path, const rt::Program& program, sim::Observation base);

}  // namespace cbtl::app
