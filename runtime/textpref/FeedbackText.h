// FeedbackText.h — reading a yes/no out of a user's free-text reaction, for the offline descriptor model.
//
// A small transparent lexicon, not a language model: positive cue words (enjoy, love, like, great, thanks, ...),
// negative cue words (hate, dislike, boring, awful, ...), and negators (not, never, no, n't, ...) that flip the
// next cue word within three words. The score is the sum of the cue polarities; a negative cue always wins over a
// bare politeness word ("thanks, but I did not enjoy it" is negative). No cue at all gives nullopt: the record is
// kept in the history but not learned from by the offline model.
#pragma once

#include <optional>
#include <string_view>

namespace cbtl::textpref {

std::optional<bool> classifyFeedbackText(std::string_view text);

}  // namespace cbtl::textpref
