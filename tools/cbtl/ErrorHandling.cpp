#include "tools/cbtl/ErrorHandling.h"

#include "runtime/core/InternalError.h"
#include "runtime/core/Values.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <exception>
#include <new>

namespace cbtl::cli {

namespace {

std::string prefix(const std::string& command) { return command.empty() ? "cbtl" : "cbtl " + command; }

void printError(const std::string& command, const char* what) {
  fmt::print(stderr, "{}: error: {}\n", prefix(command), what);
}

int printInternal(const std::string& command, const char* what) {
  fmt::print(stderr, "{}: error: internal error: {}\nthis is a bug; please report it with the command line.\n",
             prefix(command), what);
  return kExitInternal;
}

}  // namespace

int reportCurrentException(const std::string& command) {
  try {
    throw;
  } catch (const UsageError& e) {
    printError(command, e.what());
    return kExitUsage;
  } catch (const model::ProfileError& e) {
    printError(command, e.what());
    return kExitBadInput;
  } catch (const rt::RuntimeError& e) {
    printError(command, e.what());
    return kExitBadInput;
  } catch (const CLI::ConstructionError& e) {  // a command declared its options wrongly
    return printInternal(command, e.what());
  } catch (const std::logic_error& e) {  // rt::InternalError and every other broken invariant
    return printInternal(command, e.what());
  } catch (const std::runtime_error& e) {
    printError(command, e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    return printInternal(command, "out of memory");
  } catch (const std::exception& e) {
    return printInternal(command, e.what());
  } catch (...) {
    return printInternal(command, "an exception of unknown type");
  }
}

void runCommand(const std::string& command, int& exitCode, const std::function<int()>& body) {
  try {
    exitCode = body();
  } catch (const CLI::ParseError&) {
    throw;  // CLI11's own usage errors; main() prints them through app.exit() and exits 2
  } catch (...) {
    exitCode = reportCurrentException(command);
  }
}

}  // namespace cbtl::cli
