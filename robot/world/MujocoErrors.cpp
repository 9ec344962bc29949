#include "robot/world/MujocoErrors.h"

#include <mujoco/mujoco.h>

#include <mutex>

namespace cbtl::world {
namespace {

// MuJoCo calls this from C code; throwing through it is what its documentation recommends for C++
// users (the default handler exits the process).
void onError(const char* msg) { throw MujocoError(std::string("MuJoCo error: ") + msg); }

void onWarning(const char*) {}

}  // namespace

void installMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = onError;
    mju_user_warning = onWarning;
  });
}

}  // namespace cbtl::world
