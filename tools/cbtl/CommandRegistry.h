// CommandRegistry.h — how `cbtl` subcommands join the command line.
//
// Each subcommand lives in its own tools/cbtl/<Name>Command.cpp and registers a factory with a file-scope
// `RegisterCommand` object. main() asks every factory, in `order`, to add its CLI11 subcommand to the app.
// The factory's callback stores the command's exit code in `exitCode` (0 ok, 1 bad input, 2 usage,
// 70 internal error); it must not call exit() so that the app can clean up.
#pragma once

#include <CLI/CLI.hpp>

#include <vector>

namespace cbtl::cli {

using CommandFactory = void (*)(CLI::App& app, int& exitCode);

struct CommandEntry {
  int order;  // position in --help; smaller first
  CommandFactory factory;
};

// All registered commands, in registration order (sorted by main()).
std::vector<CommandEntry>& registeredCommands();

struct RegisterCommand {
  RegisterCommand(int order, CommandFactory factory) { registeredCommands().push_back({order, factory}); }
};

}  // namespace cbtl::cli
