// CommandRun.h — runs the cbtl binary (path CBTL_BINARY) with a shell command line and captures its exit code
// and its stdout and stderr together.
#pragma once

#include <sys/wait.h>
#include <cstdio>
#include <string>

namespace cbtl::textpref::testing {

struct CommandRun {
  int exitCode = -1;
  std::string output;
};

// `environment` is prepended to the command (e.g. "OPENAI_API_KEY=sk-... "); `arguments` follow the binary.
inline CommandRun runCbtl(const std::string& arguments, const std::string& environment = {}) {
  CommandRun run;
  const std::string command = environment + std::string(CBTL_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) run.output += buffer;
  const int status = ::pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// How often `needle` occurs in `haystack`.
inline int occurrences(const std::string& haystack, const std::string& needle) {
  int n = 0;
  for (auto at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + needle.size())) ++n;
  return n;
}

}  // namespace cbtl::textpref::testing
