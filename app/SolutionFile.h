// SolutionFile.h — a solution `cbtl solve --format json` wrote, read back as the moment feedback is about
// (`cbtl feedback --solution sol.json`): the task, its full assignment and the observation it was solved under,
// each value checked against its declaration in the program given now.
#pragma once

#include "runtime/core/Program.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::app {

// Bad input: the file, the JSON Pointer of the offending value and what was expected.
struct SolutionFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SolutionMoment {
  std::string task;
  std::vector<double> assignment;   // laid out as the program's slots say; variables outside the task at their init
  std::vector<double> observation;  // laid out as observationSlots() says
  std::string text;                 // the file as read, for provenance
};

// The file must be a cbtl-solution (version 1) whose status is "solved", for a task of `program`, giving every
// variable of that task and every observation of the program.
SolutionMoment readSolutionFile(const std::string& path, const rt::Program& program);

}  // namespace cbtl::app
