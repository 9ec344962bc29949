// cbtl — run, solve and inspect CBTL constraint graphs. Subcommands register themselves (CommandRegistry.h).
#include "CommandRegistry.h"
#include "ErrorHandling.h"

#include <algorithm>

int main(int argc, char** argv) {
  CLI::App app{"cbtl: run CBTL constraint graphs: solve, personalize, learn, render"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cbtl 0.1.0");

  int exitCode = 0;
  auto& commands = cbtl::cli::registeredCommands();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.factory(app, exitCode);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (...) {  // commands catch their own (ErrorHandling.h); this is for anything thrown outside them
    return cbtl::cli::reportCurrentException("");
  }
  return exitCode;
}
