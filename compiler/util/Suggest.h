// Suggest.h — "did you mean" suggestions by edit distance.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cbtl {

// Levenshtein distance (insertions, deletions, substitutions, and adjacent transpositions count 1).
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate closest to `word`, if it is close enough to be a plausible typo (distance at most 1 for
// words of up to 4 characters, otherwise at most a third of the word's length, and never the word itself).
// Ties go to the candidate that comes first in `candidates`, so callers control determinism.
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

// The error for a command-line word that is none of `commands` ("cbtl: error: 'repll' is not a cbtl command; did
// you mean 'repl'?" and where to look), or empty when it is one of them.
std::string unknownCommandMessage(std::string_view program, std::string_view word,
                                  const std::vector<std::string>& commands);

}  // namespace cbtl
