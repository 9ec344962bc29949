#include "tools/cbtl/CommandRegistry.h"

namespace cbtl::cli {

std::vector<CommandEntry>& registeredCommands() {
  // A function-local static: initialised on first use, so registration order across files is safe.
  static std::vector<CommandEntry> commands;
  return commands;
}

}  // namespace cbtl::cli
