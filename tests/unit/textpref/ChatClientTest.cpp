// The real libcurl client against the loopback chat-completions server: ratings, split numerals, broken
// responses, retries, timeouts and quota errors.
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/TextPreferenceModel.h"

#include <cstdlib>
#include <thread>

namespace cbtl::textpref::testing {
namespace {

TEST(ChatClient, DigitRatingsGiveExpectedProbabilityAndSendTheProtocolFields) {
  Harness h;
  h.server.push(replyRating({{"8", 0.6}, {"7", 0.3}, {"9", 0.1}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_NEAR(a.value().probability, 0.8 * 0.6 + 0.7 * 0.3 + 0.9 * 0.1, 1e-9);
  EXPECT_NEAR(a.value().ratings.p[8], 0.6, 1e-9);
  EXPECT_NEAR(a.value().entropyBits, bernoulliEntropyBits(a.value().probability), 1e-12);
  EXPECT_EQ(a.value().provenance, "openai-compatible:test-model");

  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 1u);
  const auto& body = requests[0].body;
  EXPECT_EQ(requests[0].path, "/v1/chat/completions");
  EXPECT_EQ(body["model"], "test-model");
  EXPECT_EQ(body["logprobs"], true);
  EXPECT_EQ(body["top_logprobs"], 20);
  EXPECT_EQ(body["max_tokens"], 1);
  EXPECT_EQ(body["temperature"], 0.0);
  EXPECT_EQ(body["seed"], 3);
  ASSERT_EQ(body["messages"].size(), 1u);
  EXPECT_EQ(body["messages"][0]["role"], "user");
  EXPECT_NE(body["messages"][0]["content"].get<std::string>().find("Cosmos"), std::string::npos);
  EXPECT_NE(body["messages"][0]["content"].get<std::string>().find("Unknown"), std::string::npos);
}

TEST(ChatClient, ConfigurableMaxTokensFieldName) {
  Harness h;
  h.server.push(replyRating({{"5", 1.0}}));
  ChatConfig c = h.config();
  c.maxTokensField = "max_completion_tokens";
  LlmPreferenceModel model(h.client(c), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  const auto body = h.server.requests().at(0).body;
  EXPECT_EQ(body["max_completion_tokens"], 1);
  EXPECT_FALSE(body.contains("max_tokens"));
}

TEST(ChatClient, NumberedOptionsWithoutRenormalisationMatchTheReferenceCode) {
  Harness h;
  // Option 9 is rating 8, option 11 is rating 10; 0.3 of the mass is on other tokens and counts as rating 0.
  h.server.push(replyRating({{"9", 0.5}, {"11", 0.2}, {"Sure", 0.3}}));
  LlmPreferenceModel model(h.client(), referenceParityOptions(examplePrompts()));
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_NEAR(a.value().probability, 0.8 * 0.5 + 1.0 * 0.2, 1e-9);
  EXPECT_NEAR(a.value().ratings.coverage, 0.7, 1e-9);
  EXPECT_FALSE(a.value().ratings.renormalized);
  const auto body = h.server.requests().at(0).body;
  EXPECT_EQ(body["top_logprobs"], 11);
  EXPECT_NE(body["messages"][0]["content"].get<std::string>().find("11. 10"), std::string::npos);
}

TEST(ChatClient, DigitRatingsRenormaliseOverTheElevenAnswers) {
  Harness h;
  h.server.push(replyRating({{"10", 0.4}, {" 0", 0.4}, {"ten", 0.2}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_NEAR(a.value().probability, 0.5, 1e-9);
  EXPECT_NEAR(a.value().ratings.coverage, 0.8, 1e-9);
  EXPECT_EQ(h.server.requestCount(), 1);  // "10" arrived as one token: no split follow-up
}

TEST(ChatClient, SplitTenIsResolvedWithAPrefilledFollowUp) {
  Harness h;
  // A digit-splitting tokenizer: "1" stands for both rating 1 and the start of "10".
  h.server.push(replyRating({{"1", 0.5}, {"9", 0.5}}));
  h.server.push(replyRating({{"0", 0.8}, {"<|eot_id|>", 0.2}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_NEAR(a.value().ratings.p[10], 0.4, 1e-9);
  EXPECT_NEAR(a.value().ratings.p[1], 0.1, 1e-9);
  EXPECT_NEAR(a.value().ratings.p[9], 0.5, 1e-9);
  EXPECT_NEAR(a.value().probability, 1.0 * 0.4 + 0.1 * 0.1 + 0.9 * 0.5, 1e-9);
  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 2u);
  const auto& messages = requests[1].body["messages"];
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[1]["role"], "assistant");
  EXPECT_EQ(messages[1]["content"], "1");
}

TEST(ChatClient, SplitFollowUpCarriesServerSpecificFields) {
  Harness h;
  h.server.push(replyRating({{"1", 1.0}}));
  h.server.push(replyRating({{"0", 1.0}}));
  LlmModelOptions o = bookOptions();
  o.followUpExtraBody = {{"continue_final_message", true}, {"add_generation_prompt", false}};
  LlmPreferenceModel model(h.client(), o);
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_DOUBLE_EQ(a.value().probability, 1.0);
  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_FALSE(requests[0].body.contains("continue_final_message"));
  EXPECT_EQ(requests[1].body["continue_final_message"], true);
  EXPECT_EQ(requests[1].body["add_generation_prompt"], false);
}

TEST(ChatClient, ExtraFieldsMayNotOverrideCoreFields) {
  Harness h;
  auto client = h.client();
  ChatRequest request;
  request.messages = {{"user", "x"}};
  request.extraBody = {{"model", "other"}};
  auto r = client->complete(request);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::Configuration);
  EXPECT_EQ(h.server.requestCount(), 0);
}

TEST(ChatClient, SplitPolicyNeverKeepsTheMergedMassOnRatingOne) {
  Harness h;
  h.server.push(replyRating({{"1", 0.5}, {"9", 0.5}}));
  LlmModelOptions o = bookOptions();
  o.split = SplitPolicy::Never;
  LlmPreferenceModel model(h.client(), o);
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a.value().ratings.p[1], 0.5, 1e-9);
  EXPECT_EQ(h.server.requestCount(), 1);
}

TEST(ChatClient, MissingLogprobsIsAnErrorAndTheCallerFallsBack) {
  Harness h;
  h.server.push(reply(200, textBody("7")));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::NoLogprobs);
  EXPECT_NE(a.error().describe().find("127.0.0.1:" + std::to_string(h.server.port())), std::string::npos);
  const Assessment fallback = assessOrFallback(a, FallbackPolicy{0.5});
  EXPECT_DOUBLE_EQ(fallback.probability, 0.5);
  EXPECT_DOUBLE_EQ(fallback.entropyBits, 1.0);
  EXPECT_EQ(fallback.provenance, "fallback: no-logprobs");
}

TEST(ChatClient, MissingLogprobsCanDegradeToAPointEstimate) {
  Harness h;
  h.server.push(reply(200, textBody("7")));
  LlmModelOptions o = bookOptions();
  o.pointEstimateWithoutLogprobs = true;
  LlmPreferenceModel model(h.client(), o);
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok());
  EXPECT_DOUBLE_EQ(a.value().probability, 0.7);
  EXPECT_NE(a.value().provenance.find("point-estimate"), std::string::npos);
}

TEST(ChatClient, WordsInsteadOfDigitsAreAnUnusableRating) {
  Harness h;
  h.server.push(replyRating({{"eight", 0.9}, {"8", 0.1}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::UnusableRating);
}

TEST(ChatClient, MalformedJsonIsAnErrorNamingServerAndStatus) {
  Harness h;
  h.server.push(reply(200, "{\"choices\": [ {\"message\": "));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::MalformedResponse);
  EXPECT_EQ(a.error().httpStatus, 200);
  EXPECT_EQ(a.error().server, "127.0.0.1:" + std::to_string(h.server.port()));
  EXPECT_NE(a.error().describe().find("127.0.0.1"), std::string::npos);
}

TEST(ChatClient, JsonWithoutChoicesIsMalformed) {
  Harness h;
  h.server.push(reply(200, "{\"object\": \"chat.completion\"}"));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::MalformedResponse);
}

TEST(ChatClient, RateLimitHonoursRetryAfterSeconds) {
  Harness h;
  h.server.push(reply(429, errorBody("Rate limit reached", "requests", "rate_limit_exceeded"), {{"Retry-After", "2"}}));
  h.server.push(replyRating({{"6", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_DOUBLE_EQ(a.value().probability, 0.6);
  EXPECT_EQ(h.sleeps, std::vector<long>{2000});
  EXPECT_EQ(h.server.requestCount(), 2);
}

TEST(ChatClient, RetryAfterMillisecondsTakesPrecedence) {
  Harness h;
  h.server.push(reply(429, errorBody("slow down", "requests", "rate_limit_exceeded"),
                      {{"retry-after-ms", "250"}, {"Retry-After", "9"}}));
  h.server.push(replyRating({{"6", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  EXPECT_EQ(h.sleeps, std::vector<long>{250});
}

TEST(ChatClient, ServiceUnavailableIsRetriedWithCappedJitteredBackoff) {
  Harness h;
  h.server.push(reply(503, errorBody("overloaded", "server_error", "server_is_overloaded")));
  h.server.push(reply(503, errorBody("overloaded", "server_error", "server_is_overloaded")));
  h.server.push(reply(502, "bad gateway"));
  h.server.push(replyRating({{"3", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  ASSERT_EQ(h.sleeps.size(), 3u);
  // base 100 ms doubling, capped at 400 ms, times a jitter factor in [0.75, 1].
  EXPECT_GE(h.sleeps[0], 75);
  EXPECT_LE(h.sleeps[0], 100);
  EXPECT_GE(h.sleeps[1], 150);
  EXPECT_LE(h.sleeps[1], 200);
  EXPECT_GE(h.sleeps[2], 300);
  EXPECT_LE(h.sleeps[2], 400);
}

TEST(ChatClient, RetriesAreBoundedAndTheErrorNamesServerAndStatus) {
  Harness h;
  h.server.setDefault(reply(503, errorBody("overloaded", "server_error", "server_is_overloaded")));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::HttpStatus);
  EXPECT_EQ(a.error().httpStatus, 503);
  EXPECT_EQ(a.error().attempts, 4);
  EXPECT_EQ(h.server.requestCount(), 4);
  const std::string text = a.error().describe();
  EXPECT_NE(text.find("127.0.0.1:" + std::to_string(h.server.port())), std::string::npos) << text;
  EXPECT_NE(text.find("503"), std::string::npos) << text;
  EXPECT_NE(text.find("overloaded"), std::string::npos) << text;
}

TEST(ChatClient, QuotaErrorIsNeverRetried) {
  Harness h;
  h.server.setDefault(reply(429,
                            errorBody("You exceeded your current quota", "insufficient_quota", "insufficient_quota"),
                            {{"Retry-After", "1"}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::QuotaExceeded);
  EXPECT_EQ(a.error().httpStatus, 429);
  EXPECT_EQ(h.server.requestCount(), 1);
  EXPECT_TRUE(h.sleeps.empty());
}

TEST(ChatClient, OtherClientErrorsAreNotRetried) {
  Harness h;
  h.server.setDefault(reply(400, errorBody("logprobs are not supported with reasoning models", "invalid_request_error",
                                           "unsupported_parameter")));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::HttpStatus);
  EXPECT_EQ(a.error().httpStatus, 400);
  EXPECT_NE(a.error().message.find("reasoning models"), std::string::npos);
  EXPECT_EQ(h.server.requestCount(), 1);
}

TEST(ChatClient, SlowServerHitsTheRequestTimeout) {
  Harness h;
  h.server.push([&h](const httplib::Request&, httplib::Response& res) {
    for (int i = 0; i < 50 && !h.server.stopping(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    res.set_content(ratingBody({{"5", 1.0}}), "application/json");
  });
  ChatConfig c = h.config();
  c.requestTimeoutMs = 200;
  c.retry.maxAttempts = 1;
  LlmPreferenceModel model(h.client(c), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::Timeout);
  EXPECT_EQ(a.error().attempts, 1);
  EXPECT_NE(a.error().describe().find("127.0.0.1"), std::string::npos);
}

TEST(ChatClient, TimeoutsAreRetriedWithinTheAttemptBudget) {
  Harness h;
  h.server.push([&h](const httplib::Request&, httplib::Response& res) {
    for (int i = 0; i < 50 && !h.server.stopping(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    res.set_content(ratingBody({{"5", 1.0}}), "application/json");
  });
  h.server.push(replyRating({{"4", 1.0}}));
  ChatConfig c = h.config();
  c.requestTimeoutMs = 300;
  c.retry.maxAttempts = 2;
  LlmPreferenceModel model(h.client(c), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_DOUBLE_EQ(a.value().probability, 0.4);
  EXPECT_EQ(h.sleeps.size(), 1u);
}

TEST(ChatClient, ConnectionRefusedIsATransportError) {
  std::string deadUrl;
  {
    ChatTestServer gone;
    deadUrl = gone.baseUrl();
  }
  Harness h;
  ChatConfig c = h.config();
  c.baseUrl = deadUrl;
  c.retry.maxAttempts = 2;
  LlmPreferenceModel model(h.client(c), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::Transport);
  EXPECT_EQ(a.error().attempts, 2);
}

TEST(ChatClient, InvalidTopLogprobsIsRejectedBeforeAnyRequest) {
  Harness h;
  LlmModelOptions o = bookOptions();
  o.topLogprobs = 21;
  LlmPreferenceModel model(h.client(), o);
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::Configuration);
  EXPECT_EQ(h.server.requestCount(), 0);
}

TEST(ChatClient, InvalidUtf8InAnItemNeverThrows) {
  Harness h;
  h.server.push(replyRating({{"5", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  auto a = model.assess(Item{std::string("Caf\xC3\x28 book"), {}}, {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_EQ(h.server.requestCount(), 1);
}

TEST(ChatClient, ApiKeyIsSentOnlyAsAuthorizationHeader) {
  Harness h;
  ::setenv(kKeyVariable, "sk-test-secret-123", 1);
  h.server.push(replyRating({{"5", 1.0}}));
  h.server.push(reply(401, errorBody("Incorrect API key provided", "invalid_request_error", "invalid_api_key")));
  LlmPreferenceModel model(h.client(), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  auto failed = model.assess(Item{"Moby Dick", {}}, {});
  ::unsetenv(kKeyVariable);
  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0].authorization, "Bearer sk-test-secret-123");
  EXPECT_EQ(requests[0].body.dump().find("sk-test"), std::string::npos);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().httpStatus, 401);
  EXPECT_EQ(failed.error().describe().find("sk-test"), std::string::npos);
  EXPECT_EQ(model.saveState().dump().find("sk-test"), std::string::npos);
}

TEST(ChatClient, NoAuthorizationHeaderWithoutAKey) {
  Harness h;
  ::unsetenv(kKeyVariable);
  h.server.push(replyRating({{"5", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  EXPECT_EQ(h.server.requests().at(0).authorization, "");
}

TEST(LlmPreferenceModel, LearningPromptRewritesThetaFromTheWholeHistory) {
  Harness h;
  h.server.push(reply(200, textBody("  Liked books so far: Cosmos. Disliked books so far: none.  ")));
  h.server.push(reply(200, textBody("Liked books so far: Cosmos. Disliked books so far: Moby Dick.")));
  LlmPreferenceModel model(h.client(), bookOptions());
  EXPECT_EQ(model.thetaText(), "Unknown");
  FeedbackRecord first{testBook(), {}, "I loved it", true};
  ASSERT_TRUE(model.learn(std::span(&first, 1)).ok());
  EXPECT_EQ(model.thetaText(), "Liked books so far: Cosmos. Disliked books so far: none.");
  FeedbackRecord second{Item{"Moby Dick", {}}, {}, "Too long and dull", false};
  ASSERT_TRUE(model.learn(std::span(&second, 1)).ok());
  EXPECT_EQ(model.history().size(), 2u);

  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 2u);
  const auto& body = requests[1].body;
  EXPECT_FALSE(body.contains("logprobs"));
  EXPECT_EQ(body["temperature"], 1.0);
  EXPECT_EQ(body["max_tokens"], 400);
  const std::string prompt = body["messages"][0]["content"];
  EXPECT_NE(prompt.find("I loved it"), std::string::npos);  // the whole history is re-sent
  EXPECT_NE(prompt.find("Too long and dull"), std::string::npos);
  EXPECT_NE(prompt.find("Disliked books so far: none."), std::string::npos);  // with the current theta
}

// A server that echoes the key in its learning reply: the summary that is stored (and saved in profiles) holds
// "[redacted]" instead, for the key itself and for anything that looks like a credential.
TEST(LlmPreferenceModel, TheLearnedSummaryNeverHoldsTheKey) {
  Harness h;
  ::setenv(kKeyVariable, "key-echo-secret-789", 1);
  h.server.push(reply(200, textBody("Likes astronomy. You sent key-echo-secret-789 as Bearer abcdefgh12345678.")));
  LlmPreferenceModel model(h.client(), bookOptions());
  FeedbackRecord record{testBook(), {}, "great", true};
  ASSERT_TRUE(model.learn(std::span(&record, 1)).ok());
  EXPECT_EQ(model.thetaText(), "Likes astronomy. You sent [redacted] as Bearer [redacted].");
  EXPECT_EQ(model.saveState().dump().find("key-echo"), std::string::npos);
  // A summary saved before redaction existed is scrubbed when it is loaded.
  nlohmann::json old = model.saveState();
  old["theta"] = "Likes astronomy; key-echo-secret-789";
  LlmPreferenceModel reloaded(h.client(), bookOptions());
  ASSERT_TRUE(reloaded.loadState(old).ok());
  ::unsetenv(kKeyVariable);
  EXPECT_EQ(reloaded.thetaText(), "Likes astronomy; [redacted]");
}

TEST(LlmPreferenceModel, FailedLearningKeepsThetaAndReportsTheError) {
  Harness h;
  h.server.setDefault(reply(500, "internal"));
  ChatConfig c = h.config();
  c.retry.maxAttempts = 2;
  LlmPreferenceModel model(h.client(c), bookOptions());
  FeedbackRecord record{testBook(), {}, "great", true};
  Status s = model.learn(std::span(&record, 1));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().httpStatus, 500);
  EXPECT_EQ(model.thetaText(), "Unknown");
  EXPECT_EQ(model.history().size(), 1u);
}

TEST(LlmPreferenceModel, StateRoundTripsAndCorruptStateIsRejected) {
  Harness h;
  h.server.push(reply(200, textBody("Likes astronomy.")));
  LlmPreferenceModel model(h.client(), bookOptions());
  FeedbackRecord record{testBook(), {}, "great", true};
  ASSERT_TRUE(model.learn(std::span(&record, 1)).ok());
  LlmPreferenceModel restored(h.client(), bookOptions());
  ASSERT_TRUE(restored.loadState(model.saveState()).ok());
  EXPECT_EQ(restored.thetaText(), "Likes astronomy.");
  EXPECT_EQ(restored.history(), model.history());

  nlohmann::json broken = model.saveState();
  broken["history"][0]["item"] = 42;
  Status s = restored.loadState(broken);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, ErrorKind::InvalidState);
  EXPECT_EQ(restored.thetaText(), "Likes astronomy.");  // unchanged
}

}  // namespace
}  // namespace cbtl::textpref::testing
