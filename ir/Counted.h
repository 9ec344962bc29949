// Counted.h — "1 task", "3 tasks": a count with its noun, for the summaries the graph printer, cbtlc and the REPL
// print. Nouns here are regular (plural = noun + "s").
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace cbtl::ir {

inline std::string counted(std::size_t n, std::string_view noun) {
  return std::to_string(n) + " " + std::string(noun) + (n == 1 ? "" : "s");
}

}  // namespace cbtl::ir
