// ChildProcess.h — a program run through `/bin/sh -c COMMAND` that talks in lines on its standard input and
// output: the transport of the external simulator protocol (SimulatorProtocol.h).
//
// Never hangs and never kills the caller: every read waits at most the timeout it is given; a write to a
// program that has exited reports that instead of raising SIGPIPE (its stdin is a socket written with
// MSG_NOSIGNAL); the destructor closes the program's stdin, waits briefly for it to leave, then kills its whole
// process group (the shell and what it started).
//
// What the program writes on stderr is passed through to this process's stderr, each line prefixed with
// `stderrPrefix`, as it is read (during readLine), and its last lines are kept for error messages.
//
// One thread at a time: a ChildProcess is not safe for concurrent use.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <deque>
#include <string>

namespace cbtl::sim {

class ChildProcess {
 public:
  // Starts `command` with working directory `workingDirectory` (empty: this process's). Throws
  // std::runtime_error when the program cannot be started (no shell, no such folder).
  ChildProcess(const std::string& command, const std::string& workingDirectory, std::string stderrPrefix);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Writes `line` and a newline. False when the program no longer reads (it exited or closed its stdin).
  bool writeLine(const std::string& line);

  enum class ReadOutcome {
    Line,      // `line` holds the next line, without its newline
    Closed,    // the program closed its stdout (usually: it exited); exitDescription() says how it ended
    TimedOut,  // nothing complete arrived within the timeout
    TooLong,   // the line exceeded maxLineBytes (the program is then stopped)
  };
  ReadOutcome readLine(std::string& line, int timeoutMs, std::size_t maxLineBytes = 64u << 20);

  // Closes stdin (end of input for the program), waits up to `graceMs` for it to exit, then kills the group.
  void stop(int graceMs);

  // "exited with status 1", "was killed by signal 11 (Segmentation fault)", or "is still running".
  std::string exitDescription();

  // The program's last lines on stderr (at most 20), oldest first, each prefixed "  | ".
  std::string stderrTail() const;

  pid_t pid() const { return pid_; }

 private:
  // Reads what stderr holds now and passes its complete lines on; at its end, the incomplete last line too.
  void drainStderr(bool untilEnd);
  // drainStderr until stderr is closed or `ms` have passed (the program may keep stderr open).
  void drainStderrFor(int ms);
  bool reap(bool wait);

  pid_t pid_ = -1;
  int stdinFd_ = -1, stdoutFd_ = -1, stderrFd_ = -1;
  std::string stdoutBuffer_, stderrBuffer_;
  std::deque<std::string> stderrLines_;
  std::string stderrPrefix_;
  bool reaped_ = false;
  int status_ = 0;
};

}  // namespace cbtl::sim
