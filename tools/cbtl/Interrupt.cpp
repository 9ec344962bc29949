#include "tools/cbtl/Interrupt.h"

#include <fmt/core.h>

#include <unistd.h>
#include <csignal>

namespace cbtl::cli {
namespace {

std::vector<std::string>& storedCommandLine() {
  static std::vector<std::string> words;
  return words;
}

// Set once before the handlers are installed and never changed after: the handler only reads it.
std::string& interruptText() {
  static std::string text;
  return text;
}

extern "C" void onInterrupt(int signal) {
  const std::string& text = interruptText();
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + written, text.size() - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::_exit(128 + signal);
}

std::string shellQuoted(const std::string& word) {
  if (!word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%") ==
          std::string::npos)
    return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

void setCommandLine(int argc, char** argv) {
  storedCommandLine().assign(argv, argv + argc);  // argv[0] as typed, so that the command can be pasted back
}

const std::vector<std::string>& commandLine() { return storedCommandLine(); }

std::string resumeCommand(const std::vector<std::string>& words) {
  std::string text;
  bool resume = false;
  for (const std::string& w : words) {
    if (w == "--force") continue;
    resume = resume || w == "--resume";
    text += (text.empty() ? "" : " ") + shellQuoted(w);
  }
  return resume ? text : text + " --resume";
}

void sayOnInterrupt(std::string message) {
  interruptText() = std::move(message);
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
}

std::string interruptMessage(const std::string& command, const std::string& out, const std::string& kept) {
  if (out.empty())
    return fmt::format("\ncbtl {}: interrupted; nothing was kept (no --out folder was given)\n", command);
  return fmt::format("\ncbtl {}: interrupted; {} stays in {}; continue with:\n  {}\n", command, kept, out,
                     resumeCommand(commandLine()));
}

}  // namespace cbtl::cli
