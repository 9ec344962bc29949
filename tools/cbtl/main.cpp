// cbtl — run, solve and inspect CBTL constraint graphs. Subcommands register themselves (CommandRegistry.h).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{"cbtl: run CBTL constraint graphs: solve, personalize, learn, render"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cbtl 0.1.0");

  int exitCode = 0;
  auto& commands = cbtl::cli::registeredCommands();
  std::stable_sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.factory(app, exitCode);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // A usage error names the command it belongs to, like every other error of cbtl.
    std::string command = "cbtl";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      command += " " + sub->get_name();
    }
    fmt::print(stderr, "{}: error: {}\nRun '{} --help' for more information.\n", command, e.what(), command);
    return 2;
  } catch (...) {  // commands catch their own (ErrorHandling.h); this is for anything thrown outside them
    return cbtl::cli::reportCurrentException("");
  }
  return exitCode;
}
