// InternalError.h — the exception for a broken contract inside CBTL itself (a bug, not bad input).
//
// Throw rt::InternalError when the runtime reaches a state that correct code cannot produce, e.g. a domain
// simulator that answers sim::ActionStatus::UnknownAction to a call the compiled program made. It derives
// from std::logic_error, so a front end that maps std::logic_error to "internal error, this is a bug"
// (`cbtl` exits 70) treats it like every other broken invariant. Bad input (a malformed file, an option out
// of range) is never an InternalError: that is rt::RuntimeError, model::ProfileError or std::runtime_error.
#pragma once

#include <stdexcept>
#include <string>

namespace cbtl::rt {

struct InternalError : std::logic_error {
  using std::logic_error::logic_error;
};

}  // namespace cbtl::rt
