#include "robot/world/MujocoErrors.h"

#include <mujoco/mujoco.h>

#include <atomic>
#include <mutex>

namespace cbtl::world {
namespace {

std::atomic<long> gWarnings{0};
std::mutex gWarningMutex;
std::string gLastWarning;

// MuJoCo calls this from C code; throwing through it is what its documentation recommends for C++
// users (the default handler exits the process).
void onError(const char* msg) { throw MujocoError(std::string("MuJoCo error: ") + msg); }

void onWarning(const char* msg) {
  gWarnings.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard lock(gWarningMutex);
  gLastWarning = msg;
}

}  // namespace

void installMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = onError;
    mju_user_warning = onWarning;
  });
}

long mujocoWarningCount() { return gWarnings.load(std::memory_order_relaxed); }

std::string lastMujocoWarning() {
  std::lock_guard lock(gWarningMutex);
  return gLastWarning;
}

}  // namespace cbtl::world
