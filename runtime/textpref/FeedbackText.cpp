#include "runtime/textpref/FeedbackText.h"

#include <array>
#include <cctype>
#include <string>
#include <vector>

namespace cbtl::textpref {
namespace {

// Word stems; a word matches a stem when it starts with it ("enjoyed" matches "enjoy").
constexpr std::array<std::string_view, 14> kPositive = {"enjoy",     "love",     "like",      "great", "wonderful",
                                                        "amazing",   "perfect",  "excellent", "good",  "fantastic",
                                                        "favourite", "favorite", "delight",   "yes"};
constexpr std::array<std::string_view, 12> kNegative = {"hate", "dislike",    "boring", "bored",    "awful", "terrible",
                                                        "bad",  "disappoint", "worst",  "horrible", "meh",   "dull"};
constexpr std::array<std::string_view, 3> kPolite = {"thank", "thanks", "thx"};
constexpr std::array<std::string_view, 8> kNegators = {"not",    "no",    "never",  "don't",
                                                       "didn't", "isn't", "wasn't", "nothing"};

template <std::size_t N>
bool startsWithAny(const std::string& word, const std::array<std::string_view, N>& stems) {
  for (auto stem : stems)
    if (word.rfind(stem, 0) == 0) return true;
  return false;
}

template <std::size_t N>
bool equalsAny(const std::string& word, const std::array<std::string_view, N>& words) {
  for (auto w : words)
    if (word == w) return true;
  return false;
}

}  // namespace

std::optional<bool> classifyFeedbackText(std::string_view text) {
  std::vector<std::string> words;
  std::string current;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalpha(u) || c == '\'') {
      current.push_back(static_cast<char>(std::tolower(u)));
    } else if (!current.empty()) {
      words.push_back(current);
      current.clear();
    }
  }
  if (!current.empty()) words.push_back(current);

  int score = 0;
  bool anyNegative = false;
  bool anyCue = false;
  bool polite = false;
  int negateWithin = 0;  // > 0: the next cue word within this many words is flipped
  for (const auto& w : words) {
    const bool negator = equalsAny(w, kNegators) || (w.size() > 3 && w.ends_with("n't"));
    if (negator) {
      negateWithin = 3;
      continue;
    }
    int polarity = 0;
    if (startsWithAny(w, kNegative))
      polarity = -1;
    else if (startsWithAny(w, kPositive))
      polarity = +1;
    else if (equalsAny(w, kPolite))
      polite = true;
    if (polarity != 0) {
      if (negateWithin > 0) polarity = -polarity;
      negateWithin = 0;
      score += polarity;
      anyCue = true;
      if (polarity < 0) anyNegative = true;
    } else if (negateWithin > 0) {
      --negateWithin;
    }
  }
  if (!anyCue) {
    if (polite) return true;  // a bare "thank you" is mild approval
    return std::nullopt;
  }
  if (anyNegative && score <= 0) return false;
  if (score > 0) return true;
  return false;
}

}  // namespace cbtl::textpref
