// MujocoErrors.h — MuJoCo's process-wide error and warning hooks.
//
// MuJoCo's default error handler prints "Press Enter to exit", waits on stdin and calls exit(1). Every
// entry point of the robot world calls installMujocoHandlers() first; after that a MuJoCo error throws
// MujocoError (a std::runtime_error) from the failing call, and warnings are dropped (nothing in the project
// reads them) instead of being appended to MUJOCO_LOG.TXT in the working directory.
// The handlers are process-global; installing them is idempotent and thread-safe.
#pragma once

#include <stdexcept>
#include <string>

namespace cbtl::world {

class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void installMujocoHandlers();

}  // namespace cbtl::world
