#include "compiler/util/Suggest.h"

#include <algorithm>
#include <limits>

namespace cbtl {

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Optimal string alignment distance with three rolling rows.
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  const std::size_t limit = word.size() <= 4 ? 1 : std::max<std::size_t>(1, word.size() / 3);
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::string bestName;
  for (const auto& c : candidates) {
    if (c == word) continue;
    const std::size_t d = editDistance(word, c);
    if (d <= limit && d < best) {
      best = d;
      bestName = c;
    }
  }
  return bestName;
}

std::string unknownCommandMessage(std::string_view program, std::string_view word,
                                  const std::vector<std::string>& commands) {
  for (const auto& c : commands)
    if (c == word) return {};
  const std::string nearest = closestMatch(word, commands);
  std::string message = "error: '" + std::string(word) + "' is not a " + std::string(program) + " command";
  if (!nearest.empty()) message += "; did you mean '" + nearest + "'?";
  return std::string(program) + ": " + message + "\nRun '" + std::string(program) + " --help' for the commands.\n";
}

}  // namespace cbtl
