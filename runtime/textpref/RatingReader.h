// RatingReader.h — from next-token log-probabilities to the 11-bin RatingDistribution.
//
// Two rating scales:
//  - Digits (the paper): the model answers the rating itself, "0".."10"; label = rating.
//  - NumberedOptions (the reference code): ratings are listed as options "1. 0" .. "11. 10" and the model
//    answers the option number; label k means rating k - 1.
// A token counts for label k only if, after trimming whitespace, it is exactly the decimal numeral of k (so
// " 8" and "8" both count; "eight", "8." and "08" do not). Probabilities of tokens with the same label add up.
//
// Split numerals. Tokenizers that cut numbers into single digits (Qwen, SmolLM, Llama 2, Mistral) never emit
// "10" or "11" as one token: the first token "1" then merges label 1 with labels 10 (and 11). The reader handles
// this with one follow-up request whose assistant turn is pre-filled with "1": from the follow-up's first-token
// distribution q, a share q("0") of the "1" mass moves to label 10, and (options scale) q("1") to label 11; the
// rest (end of turn, punctuation) stays on label 1. SplitPolicy says when the follow-up is made: Never, Always
// (whenever "1" has mass), or Auto (only when no multi-digit label appeared among the top tokens and "1" carries
// at least `splitThreshold` probability: a single-token "10" is then most likely absent for a reason).
#pragma once

#include "runtime/textpref/ChatClient.h"
#include "runtime/textpref/RatingDistribution.h"
#include "runtime/textpref/Result.h"

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace cbtl::textpref {

enum class RatingScale { Digits, NumberedOptions };
enum class SplitPolicy { Auto, Always, Never };

const char* ratingScaleName(RatingScale scale);  // "digits", "options"
std::optional<RatingScale> parseRatingScale(std::string_view name);
const char* splitPolicyName(SplitPolicy policy);  // "auto", "always", "never"
std::optional<SplitPolicy> parseSplitPolicy(std::string_view name);

// Probability mass per label 0..11 read from the first answer token.
struct LabelMass {
  std::array<double, 12> mass{};
  double operator[](int label) const { return mass[static_cast<std::size_t>(label)]; }
};

// The label a token stands for, if any (0..11, by the exact-numeral rule above).
std::optional<int> tokenLabel(std::string_view token);

// Sums exp(logprob) per label over `top` (logprob -9999 and below counts as 0).
LabelMass readLabels(std::span<const TokenLogprob> top);

// Whether a split follow-up is needed under `policy`.
bool needsSplitFollowUp(const LabelMass& labels, RatingScale scale, SplitPolicy policy, double splitThreshold);

// Moves the "1" mass to labels 10/11 according to the follow-up's first-token distribution.
LabelMass applySplitFollowUp(const LabelMass& labels, RatingScale scale, std::span<const TokenLogprob> followUp);

// The 11-bin distribution. coverage = mass on the scale's 11 labels; UnusableRating when coverage < minCoverage
// (the model did not answer in the format asked for). With `renormalize` the bins are divided by the coverage.
Result<RatingDistribution> toRatings(const LabelMass& labels, RatingScale scale, bool renormalize, double minCoverage,
                                     const std::string& server);

}  // namespace cbtl::textpref
