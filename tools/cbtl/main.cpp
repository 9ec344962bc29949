// cbtl — run, solve and inspect CBTL constraint graphs. Subcommands register themselves (CommandRegistry.h).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/HelpLayout.h"
#include "tools/cbtl/Interrupt.h"
#include "tools/common/UnknownOption.h"

#include "compiler/util/Suggest.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  cbtl::cli::setCommandLine(argc, argv);
  CLI::App app{"cbtl: run CBTL constraint graphs: solve, personalize, learn, render"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cbtl 0.1.0");

  int exitCode = 0;
  auto& commands = cbtl::cli::registeredCommands();
  std::stable_sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.factory(app, exitCode);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    cbtl::cli::arrangeHelp(sub, sub->get_name());
  app.footer(
      "\nExamples:\n  cbtl run domains/cooking/cooking.cbtl --steps 2000 --out out/cooking-0\n"
      "  cbtl solve domains/coffee/coffee.cbtl --explain\n  cbtl repl domains/feeding/feeding.cbtl\n"
      "Every command has --help; docs/tutorial.md writes a domain from scratch.\n");

  // An unknown command is named, with the nearest known one, before CLI11 calls it an unexpected argument.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      names.push_back(sub->get_name());
    if (const std::string message = cbtl::unknownCommandMessage("cbtl", argv[1], names); !message.empty()) {
      fmt::print(stderr, "{}", message);
      return 2;
    }
  }
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
    // An unexpected argument is most often a mistyped option: name it, with the nearest one.
    std::string message = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
      const CLI::App* deepest = &app;
      while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
      if (std::string unknown = cbtl::cli::unknownOptionMessage(*deepest, argc, argv); !unknown.empty())
        message = unknown;
    }
    fmt::print(stderr, "{}: error: {}\nRun '{} --help' for more information.\n", command, message, command);
    return 2;
  } catch (...) {  // commands catch their own (ErrorHandling.h); this is for anything thrown outside them
    return cbtl::cli::reportCurrentException("");
  }
  return exitCode;
}
