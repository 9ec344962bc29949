#include "tools/cbtl/Interrupt.h"

#include <fmt/core.h>

#include "runtime/textpref/RunReport.h"

#include <fcntl.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <mutex>
#include <thread>

namespace cbtl::cli {
namespace {

std::vector<std::string>& storedCommandLine() {
  static std::vector<std::string> words;
  return words;
}

// Set before the handlers are installed; the handler and the exit thread only read it.
std::string& interruptText() {
  static std::string text;
  return text;
}

void writeToStderr(const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + written, text.size() - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
}

// The first signal's number (0: none yet) and the write end of the pipe that wakes the exit thread (-1: none).
// Lock-free atomics, so the signal handler may use them.
std::atomic<int> pendingSignal{0};
std::atomic<int> wakeFd{-1};
static_assert(std::atomic<int>::is_always_lock_free);

// The signal handler only wakes the exit thread: writing llm.json takes locks and allocates, which a signal
// handler must not do. A second signal, or a process without the thread, exits at once as before.
extern "C" void onInterrupt(int signal) {
  int none = 0;
  if (pendingSignal.compare_exchange_strong(none, signal)) {
    const int fd = wakeFd.load();
    const char byte = 1;
    if (fd >= 0 && ::write(fd, &byte, 1) == 1) return;
    writeToStderr(interruptText());
  }
  ::_exit(128 + signal);
}

// Runs in its own thread, outside any signal handler: says what was kept, writes llm.json for the runs in
// progress (their fault counts live only in memory, textpref/RunReport.h), and ends the process.
void exitThread(int readFd) {
  char byte = 0;
  for (;;) {
    const ssize_t n = ::read(readFd, &byte, 1);
    if (n == 1) break;
    if (n < 0 && errno == EINTR) continue;
    wakeFd.store(-1);  // cannot wait any more: the handler exits by itself
    return;
  }
  const int signal = pendingSignal.load();
  writeToStderr(interruptText());
  try {
    textpref::writeLiveLlmReports();
  } catch (...) {  // NOLINT(bugprone-empty-catch): the exit below must happen whatever failed
  }
  ::_exit(128 + signal);
}

// Starts the exit thread once; without it (no pipe, no thread) the handler keeps the immediate exit.
void startExitThread() {
  static std::once_flag once;
  std::call_once(once, [] {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    try {
      std::thread(exitThread, fds[0]).detach();
      wakeFd.store(fds[1]);
    } catch (...) {
      ::close(fds[0]);
      ::close(fds[1]);
    }
  });
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
  startExitThread();
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
