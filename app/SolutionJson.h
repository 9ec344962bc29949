// SolutionJson.h — a solve as one JSON document (`cbtl solve --format json`), for programs that drive CBTL:
//
//   {"format": "cbtl-solution", "version": 1, "task": "feedBite",
//    "status": "solved" | "unsatisfiable" | "interrupted" | "refused",   (the outcome people and scripts test)
//    "outcome": "Solved", "replanned": false, "iterations": 124,
//    "assignment": {"platePos": [0.31, 0.30], "acquireBite.dip": "bbqSauce", ...},   (when solved)
//    "plan": [{"action": "movePlate", "args": [[0.31, 0.30]]}, ...],                 (when solved)
//    "recheck": {"constraints": 14, "variables": 6, "holds": true},
//    "constraints": [{"name": ..., "declared_at": "file:line:col", "rejected": 44, "evaluated": 39}, ...],
//    "personal": [{"instance": ..., "key": ..., "applies": true, "holds": true, "p": 1.0, "accept": 0.95,
//                  "entropy_bits": 0.0, "in_csp": true, "text": [{"factor": ..., "subject": ..., "context": ...,
//                  "theta": ...}]}, ...],                                           (at the solution)
//    "observation": {"foodOnPlate": "frenchFries", ...}}
// Values: numbers (ints as integers, bools as true/false), names as strings, vectors and poses as arrays of numbers,
// sets as arrays of names. Keys of one object appear in a fixed order, so equal solves give equal bytes.
#pragma once

#include "runtime/approach/Planner.h"

#include <string>
#include <vector>

namespace cbtl::app {

// "solved", "unsatisfiable", "interrupted" or "refused" (a solution that failed the independent re-check).
const char* solveStatus(const approach::Plan& plan);

std::string solutionJson(const approach::Plan& plan, const std::vector<double>& observation);

}  // namespace cbtl::app
