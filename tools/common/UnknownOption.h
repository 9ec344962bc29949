// UnknownOption.h — the usage error for a mistyped option, with the nearest option of its command: CLI11 only says
// "The following arguments were not expected: 10 --step", which names neither the command nor the fix.
// Header-only: both executables' main() use it on the command CLI11 was parsing when it gave up.
#pragma once

#include "compiler/util/Suggest.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace cbtl::cli {

// The options `command` and the commands above it accept, spelled as typed ("--steps", "-q").
inline std::vector<std::string> optionSpellings(const CLI::App& command) {
  std::vector<std::string> spellings;
  for (const CLI::App* app = &command; app != nullptr; app = app->get_parent()) {
    for (const CLI::Option* o : app->get_options()) {
      for (const std::string& l : o->get_lnames()) spellings.push_back("--" + l);
      for (const std::string& s : o->get_snames()) spellings.push_back("-" + s);
    }
  }
  return spellings;
}

// "unknown option '--step'; did you mean '--steps'?" for the first word of argv[1..] that looks like an option
// (a leading '-', not a number) and that `command` does not accept; empty when every such word is one it accepts.
inline std::string unknownOptionMessage(const CLI::App& command, int argc, char** argv) {
  const std::vector<std::string> known = optionSpellings(command);
  for (int i = 1; i < argc; ++i) {
    std::string word = argv[i];
    if (word == "--") break;
    if (word.size() < 2 || word[0] != '-' || (word[1] >= '0' && word[1] <= '9') || word[1] == '.') continue;
    word = word.substr(0, word.find('='));
    if (std::find(known.begin(), known.end(), word) != known.end()) continue;
    const std::string nearest = closestMatch(word, known);
    return "unknown option '" + word + "'" + (nearest.empty() ? std::string() : "; did you mean '" + nearest + "'?");
  }
  return {};
}

}  // namespace cbtl::cli
