// The 11-bin rating object, token reading, split numerals, retry arithmetic and relative scaling.
#include "runtime/textpref/RatingDistribution.h"
#include "runtime/textpref/RatingReader.h"
#include "runtime/textpref/RetryPolicy.h"
#include "runtime/textpref/TextPreferenceModel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cbtl::textpref {
namespace {

TEST(RatingDistribution, ExpectationAndEntropy) {
  auto d = RatingDistribution::pointMass(8);
  EXPECT_DOUBLE_EQ(d.expectedProbability(), 0.8);
  EXPECT_DOUBLE_EQ(bernoulliEntropyBits(0.5), 1.0);
  EXPECT_DOUBLE_EQ(bernoulliEntropyBits(0.0), 0.0);
  EXPECT_DOUBLE_EQ(bernoulliEntropyBits(1.0), 0.0);
  EXPECT_NEAR(bernoulliEntropyBits(0.25), 0.8112781244591328, 1e-12);
}

TEST(RatingDistribution, BetaBinomialHasTheBetaMean) {
  for (auto [a, b] : {std::pair{1.0, 1.0}, {2.0, 5.0}, {30.0, 3.0}, {0.5, 0.5}}) {
    const auto d = RatingDistribution::betaBinomial(a, b);
    EXPECT_NEAR(d.total(), 1.0, 1e-12);
    EXPECT_NEAR(d.expectedProbability(), a / (a + b), 1e-9);
  }
  // Beta(1,1) gives the uniform distribution over the 11 ratings.
  const auto uniform = RatingDistribution::betaBinomial(1.0, 1.0);
  for (double p : uniform.p) EXPECT_NEAR(p, 1.0 / 11.0, 1e-12);
}

TEST(RatingReader, OnlyExactNumeralsCount) {
  EXPECT_EQ(tokenLabel("8"), 8);
  EXPECT_EQ(tokenLabel(" 8"), 8);
  EXPECT_EQ(tokenLabel("10"), 10);
  EXPECT_EQ(tokenLabel("11"), 11);
  EXPECT_FALSE(tokenLabel("12").has_value());
  EXPECT_FALSE(tokenLabel("08").has_value());
  EXPECT_FALSE(tokenLabel("8.").has_value());
  EXPECT_FALSE(tokenLabel("eight").has_value());
  EXPECT_FALSE(tokenLabel("").has_value());
}

TEST(RatingReader, SameLabelTokensAddUpAndVeryNegativeLogprobsAreZero) {
  const std::vector<TokenLogprob> top{{"8", std::log(0.3)}, {" 8", std::log(0.2)}, {"3", -9999.0}};
  const auto labels = readLabels(top);
  EXPECT_NEAR(labels[8], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(labels[3], 0.0);
}

TEST(RatingReader, LowCoverageIsUnusable) {
  LabelMass labels;
  labels.mass[5] = 0.1;
  auto r = toRatings(labels, RatingScale::Digits, true, 0.5, "srv:1");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::UnusableRating);
  EXPECT_EQ(r.error().server, "srv:1");
  EXPECT_TRUE(toRatings(labels, RatingScale::Digits, true, 0.05, "srv:1").ok());
}

TEST(RatingReader, OptionsScaleShiftsLabelsByOne) {
  LabelMass labels;
  labels.mass[1] = 0.5;   // option 1 = rating 0
  labels.mass[11] = 0.5;  // option 11 = rating 10
  auto r = toRatings(labels, RatingScale::NumberedOptions, false, 0.0, "");
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r.value().p[0], 0.5);
  EXPECT_DOUBLE_EQ(r.value().p[10], 0.5);
  EXPECT_DOUBLE_EQ(r.value().expectedProbability(), 0.5);
}

TEST(RatingReader, SplitDecisionFollowsThePolicy) {
  LabelMass labels;
  labels.mass[1] = 0.3;
  labels.mass[9] = 0.7;
  EXPECT_TRUE(needsSplitFollowUp(labels, RatingScale::Digits, SplitPolicy::Auto, 0.01));
  EXPECT_FALSE(needsSplitFollowUp(labels, RatingScale::Digits, SplitPolicy::Never, 0.01));
  EXPECT_FALSE(needsSplitFollowUp(labels, RatingScale::Digits, SplitPolicy::Auto, 0.5));  // below threshold
  labels.mass[10] = 0.01;  // the tokenizer has a "10" token
  EXPECT_FALSE(needsSplitFollowUp(labels, RatingScale::Digits, SplitPolicy::Auto, 0.01));
  EXPECT_TRUE(needsSplitFollowUp(labels, RatingScale::Digits, SplitPolicy::Always, 0.01));
}

TEST(RatingReader, SplitFollowUpOnTheOptionsScaleSeparatesOneTenAndEleven) {
  LabelMass labels;
  labels.mass[1] = 0.6;
  labels.mass[5] = 0.4;
  const std::vector<TokenLogprob> next{{"0", std::log(0.25)}, {"1", std::log(0.5)}, {".", std::log(0.25)}};
  const auto out = applySplitFollowUp(labels, RatingScale::NumberedOptions, next);
  EXPECT_NEAR(out[1], 0.15, 1e-12);
  EXPECT_NEAR(out[10], 0.15, 1e-12);
  EXPECT_NEAR(out[11], 0.3, 1e-12);
  // On the digits scale a following "1" does not make a rating ("11" is not an answer).
  const auto digits = applySplitFollowUp(labels, RatingScale::Digits, next);
  EXPECT_NEAR(digits[10], 0.15, 1e-12);
  EXPECT_NEAR(digits[1], 0.45, 1e-12);
  // A space-prefixed digit is a new word, not the second digit of "10".
  const std::vector<TokenLogprob> spaced{{" 0", std::log(0.9)}};
  EXPECT_NEAR(applySplitFollowUp(labels, RatingScale::Digits, spaced)[1], 0.6, 1e-12);
}

TEST(RatingReader, NamesParse) {
  EXPECT_EQ(parseRatingScale("digits"), RatingScale::Digits);
  EXPECT_EQ(parseRatingScale("options"), RatingScale::NumberedOptions);
  EXPECT_EQ(parseSplitPolicy("always"), SplitPolicy::Always);
  EXPECT_FALSE(parseSplitPolicy("maybe").has_value());
}

TEST(RetryPolicy, Classification) {
  HttpResponse r;
  for (long s : {408L, 409L, 429L, 500L, 502L, 503L, 504L}) {
    r.status = s;
    EXPECT_EQ(classifyResponse(r), RetryDecision::Retry) << s;
  }
  for (long s : {400L, 401L, 403L, 404L, 422L}) {
    r.status = s;
    EXPECT_EQ(classifyResponse(r), RetryDecision::Fail) << s;
  }
  r.status = 200;
  EXPECT_EQ(classifyResponse(r), RetryDecision::Done);
  r.status = 429;
  r.body = R"({"error":{"message":"quota","type":"insufficient_quota","code":"insufficient_quota"}})";
  EXPECT_EQ(classifyResponse(r), RetryDecision::Quota);
  r.status = 503;
  r.body.clear();
  r.headers["x-should-retry"] = "false";
  EXPECT_EQ(classifyResponse(r), RetryDecision::Fail);
}

TEST(RetryPolicy, RetryAfterParsingAndClamping) {
  RetryPolicy p;
  p.maxRetryAfterMs = 5000;
  HttpResponse r;
  EXPECT_FALSE(retryAfterMs(r, p).has_value());
  r.headers["retry-after"] = "1.5";
  EXPECT_EQ(retryAfterMs(r, p), 1500);
  r.headers["retry-after"] = "120";
  EXPECT_EQ(retryAfterMs(r, p), 5000);
  r.headers["retry-after"] = "Wed, 21 Oct 2015 07:28:00 GMT";  // HTTP dates fall back to backoff
  EXPECT_FALSE(retryAfterMs(r, p).has_value());
  r.headers["retry-after-ms"] = "20";
  EXPECT_EQ(retryAfterMs(r, p), 20);
}

TEST(RetryPolicy, BackoffIsCappedJitteredAndSeeded) {
  RetryPolicy p;
  p.baseDelayMs = 500;
  p.maxDelayMs = 8000;
  std::mt19937_64 a(1), b(1);
  for (int k = 0; k < 10; ++k) {
    const long d = backoffDelayMs(k, p, a);
    const double raw = std::min(500.0 * std::pow(2.0, k), 8000.0);
    EXPECT_GE(d, static_cast<long>(0.75 * raw) - 1);
    EXPECT_LE(d, static_cast<long>(raw));
    EXPECT_EQ(d, backoffDelayMs(k, p, b));  // same seed, same waits
  }
}

TEST(RelativeScaling, BestAvailableItemGetsProbabilityOneAndZeroEntropy) {
  std::vector<Assessment> items(3);
  items[0].probability = 0.4;
  items[1].probability = 0.8;
  items[2].probability = 0.2;
  const auto scaled = scaleRelativeToBest(items);
  EXPECT_DOUBLE_EQ(scaled[1].probability, 1.0);
  EXPECT_DOUBLE_EQ(scaled[1].entropyBits, 0.0);
  EXPECT_DOUBLE_EQ(scaled[0].probability, 0.5);
  EXPECT_DOUBLE_EQ(scaled[0].entropyBits, 1.0);
  EXPECT_DOUBLE_EQ(scaled[2].probability, 0.25);
}

}  // namespace
}  // namespace cbtl::textpref
