// Interrupt.h — what `cbtl run` and `cbtl experiment` say when a person stops them (Ctrl-C, SIGINT; or SIGTERM):
// what was kept and the exact command that continues, instead of a bare exit 130.
//
// The run folders need no cleanup: every file is written atomically or append-only (approach/RunDirectory.h), and
// `--resume` continues from the last checkpoint whatever instant the process stopped at. One file holds what only
// memory knows: llm.json, the language model's fault counts (textpref/RunReport.h). So the signal handler only
// wakes a thread (a byte down a pipe; write(2) is async-signal-safe) that writes the prepared message, writes
// llm.json for the runs in progress (textpref::writeLiveLlmReports) and exits with 128 + the signal (130, 143).
// A second signal while that runs exits at once.
#pragma once

#include <string>
#include <vector>

namespace cbtl::cli {

// The command line main() was given, kept for the messages below.
void setCommandLine(int argc, char** argv);
const std::vector<std::string>& commandLine();

// The command line again with `--force` dropped and `--resume` added (once), each word quoted for a POSIX shell
// where it needs it.
std::string resumeCommand(const std::vector<std::string>& words);

// From now on SIGINT and SIGTERM print `message` on stderr, write llm.json for the runs in progress and end the
// process (128 + the signal).
void sayOnInterrupt(std::string message);

// The message for a command writing to `out`: empty `out` (nothing kept), else what stays and how to continue.
std::string interruptMessage(const std::string& command, const std::string& out, const std::string& kept);

}  // namespace cbtl::cli
