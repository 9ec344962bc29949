// ErrorHandling.h — the one way every `cbtl` command turns failures into messages and exit codes.
//
// A command's CLI11 callback calls `runCommand(name, exitCode, body)`. `body` returns the command's own exit code
// (0 ok, 1 bad input, 2 usage, 3 "no solution" for solve, 70 internal error); when it throws, the exception's type
// decides the code and the message, printed to stderr as `cbtl <name>: error: <what>`:
//
//   cli::UsageError                         -> 2   (a bad option value found after parsing)
//   CLI::ParseError (CLI11's own)           -> rethrown: main() prints it as a usage error, exit 2
//   model::ProfileError, rt::RuntimeError,
//   any other std::runtime_error            -> 1   (bad input: a file, a profile, a domain)
//   std::logic_error (rt::InternalError,
//   CLI::ConstructionError,
//   std::out_of_range, ...), std::bad_alloc,
//   any other exception                     -> 70  ("internal error: ... this is a bug")
//
// It never calls exit(): main() returns `exitCode` after CLI11 is done.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace cbtl::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 70;

// An option value that CLI11 accepted but the command rejects (e.g. a malformed --seeds list).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `body` and stores its exit code, or the code of the exception it threw, in `exitCode`.
void runCommand(const std::string& command, int& exitCode, const std::function<int()>& body);

// The message and exit code for the exception currently being handled (call only inside a catch block).
// Exposed so main() reports exceptions thrown outside any command the same way. `command` is what follows
// "cbtl " in the message ("run", "llm probe"); empty for none.
int reportCurrentException(const std::string& command);

}  // namespace cbtl::cli
