#include "runtime/textpref/RatingReader.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace cbtl::textpref {

const char* ratingScaleName(RatingScale scale) { return scale == RatingScale::Digits ? "digits" : "options"; }

std::optional<RatingScale> parseRatingScale(std::string_view name) {
  if (name == "digits") return RatingScale::Digits;
  if (name == "options") return RatingScale::NumberedOptions;
  return std::nullopt;
}

const char* splitPolicyName(SplitPolicy policy) {
  switch (policy) {
    case SplitPolicy::Auto:
      return "auto";
    case SplitPolicy::Always:
      return "always";
    case SplitPolicy::Never:
      return "never";
  }
  return "auto";
}

std::optional<SplitPolicy> parseSplitPolicy(std::string_view name) {
  for (SplitPolicy p : {SplitPolicy::Auto, SplitPolicy::Always, SplitPolicy::Never})
    if (name == splitPolicyName(p)) return p;
  return std::nullopt;
}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

double probabilityOf(double logprob) {
  if (!std::isfinite(logprob) || logprob <= -9999.0) return 0.0;
  return std::min(1.0, std::exp(logprob));
}

// The numeral range of the scale's 11 labels.
int firstLabel(RatingScale scale) { return scale == RatingScale::Digits ? 0 : 1; }

}  // namespace

std::optional<int> tokenLabel(std::string_view token) {
  const std::string_view t = trim(token);
  if (t.empty() || t.size() > 2) return std::nullopt;
  if (!std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
  if (t.size() == 2 && t[0] == '0') return std::nullopt;  // "08" is not a numeral we asked for
  const int value = t.size() == 1 ? t[0] - '0' : (t[0] - '0') * 10 + (t[1] - '0');
  if (value > 11) return std::nullopt;
  return value;
}

LabelMass readLabels(std::span<const TokenLogprob> top) {
  LabelMass out;
  for (const auto& entry : top)
    if (auto label = tokenLabel(entry.token))
      out.mass[static_cast<std::size_t>(*label)] += probabilityOf(entry.logprob);
  for (double& m : out.mass) m = std::min(m, 1.0);
  return out;
}

bool needsSplitFollowUp(const LabelMass& labels, RatingScale scale, SplitPolicy policy, double splitThreshold) {
  if (labels[1] <= 0.0) return false;
  switch (policy) {
    case SplitPolicy::Never:
      return false;
    case SplitPolicy::Always:
      return true;
    case SplitPolicy::Auto: {
      const bool multiDigitSeen = labels[10] > 0.0 || (scale == RatingScale::NumberedOptions && labels[11] > 0.0);
      return !multiDigitSeen && labels[1] >= splitThreshold;
    }
  }
  return false;
}

LabelMass applySplitFollowUp(const LabelMass& labels, RatingScale scale, std::span<const TokenLogprob> followUp) {
  // Only a bare digit continues the numeral; " 0" would be a new word, so the left side is not trimmed.
  double zero = 0.0;
  double one = 0.0;
  for (const auto& entry : followUp) {
    std::string_view t = entry.token;
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.remove_suffix(1);
    if (t == "0") zero += probabilityOf(entry.logprob);
    if (t == "1" && scale == RatingScale::NumberedOptions) one += probabilityOf(entry.logprob);
  }
  const double moved = std::min(1.0, zero + one);
  if (moved > 0.0 && zero + one > 1.0) {  // inconsistent top list; scale both shares down
    zero /= zero + one;
    one = 1.0 - zero;
  }
  LabelMass out = labels;
  const double base = labels[1];
  out.mass[10] += base * zero;
  out.mass[11] += base * one;
  out.mass[1] = base * (1.0 - zero - one);
  if (out.mass[1] < 0.0) out.mass[1] = 0.0;
  return out;
}

Result<RatingDistribution> toRatings(const LabelMass& labels, RatingScale scale, bool renormalize, double minCoverage,
                                     const std::string& server) {
  RatingDistribution d;
  const int first = firstLabel(scale);
  double coverage = 0.0;
  for (int r = 0; r < kRatingCount; ++r) {
    const double m = labels[first + r];
    d.p[static_cast<std::size_t>(r)] = m;
    coverage += m;
  }
  d.coverage = std::min(1.0, coverage);
  if (coverage < minCoverage || coverage <= 0.0)
    return Error{ErrorKind::UnusableRating,
                 fmt::format("only {:.3f} of the first-token probability is on the 11 rating answers (minimum {:.3f})",
                             coverage, minCoverage),
                 server};
  if (renormalize) return d.renormalize();
  if (coverage > 1.0) return d.renormalize();  // rounding in the server's numbers; keep the bins a distribution
  return d;
}

}  // namespace cbtl::textpref
