// Faults made visible and bounded: every rating that falls back and every failed learning request is counted
// by kind (FaultStats), the circuit breaker stops calling a silent server, API keys are redacted from quoted
// server messages, and a run's report (llm.json) names the backend. Servers are in-process on 127.0.0.1; no
// test asserts a duration (the ctest TIMEOUT bounds the silent-server tests).
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/CircuitBreaker.h"
#include "runtime/textpref/FaultStats.h"
#include "runtime/textpref/Redaction.h"
#include "runtime/textpref/RunReport.h"
#include "runtime/textpref/TextBackend.h"

#include <cstdlib>
#include <fstream>

namespace cbtl::textpref::testing {
namespace {

constexpr const char* kSecret = "sk-proj-TESTSECRET0123456789abcdef";

// A language-model backend aimed at the loopback server, one attempt per request unless told otherwise. The request
// timeout is generous where the server answers (a loaded machine or a sanitizer build must not turn an answer into
// a timeout); tests whose server hangs on purpose pass a short one (kHangTimeoutMs).
constexpr int kAnswerTimeoutMs = 10000, kHangTimeoutMs = 500;
TextBackendConfig backendConfig(Harness& h, int attempts = 1, int breaker = 3,
                                int requestTimeoutMs = kAnswerTimeoutMs) {
  auto config = textBackendConfigFromJson({{"backend", "openai-compatible"},
                                           {"base_url", h.server.baseUrl()},
                                           {"model", "test-model"},
                                           {"api_key_env", kKeyVariable},
                                           {"max_attempts", attempts},
                                           {"connect_timeout_ms", 1000},
                                           {"request_timeout_ms", requestTimeoutMs},
                                           {"breaker_threshold", breaker}});
  EXPECT_TRUE(config.ok());
  return config.value();
}

TEST(Redaction, ReplacesTheKeyAndKeyLikeTokens) {
  const std::string text = std::string("Incorrect API key provided: Bearer ") + kSecret + "; also " + kSecret +
                           " and sk-abcd1234efgh. Authorization: bearer xyz.123-456";
  const std::string out = redactSecrets(text, kSecret);
  EXPECT_EQ(out.find("TESTSECRET"), std::string::npos) << out;
  EXPECT_EQ(out.find("sk-abcd"), std::string::npos) << out;
  EXPECT_EQ(out.find("xyz.123"), std::string::npos) << out;
  EXPECT_NE(out.find("Incorrect API key provided: Bearer [redacted]"), std::string::npos) << out;
  EXPECT_NE(out.find("bearer [redacted]"), std::string::npos) << out;
  EXPECT_EQ(redactSecrets(out, kSecret), out);  // idempotent
}

TEST(Redaction, LeavesOrdinaryTextAlone) {
  const std::string text = "task-based risk-averse desk-lamp: HTTP 503, the bearer of bad news";
  EXPECT_EQ(redactSecrets(text), text);
  EXPECT_EQ(redactSecrets("a short key ab", "ab"), "a short key ab");  // below kMinSecretLength
  // A key that looks like nothing in particular is still removed when it is known.
  EXPECT_EQ(redactSecrets("echo: plainsecretvalue!", "plainsecretvalue"), "echo: [redacted]!");
}

TEST(Redaction, AServerEchoingTheKeyIsQuotedWithoutIt) {
  ::setenv(kKeyVariable, kSecret, 1);
  Harness h;
  h.server.setDefault(echoAuthorization(401));
  TextBackend backend(backendConfig(h), {}, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  auto a = model->assess(testBook(), {});
  ::unsetenv(kKeyVariable);
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::HttpStatus);
  EXPECT_EQ(a.error().message.find("TESTSECRET"), std::string::npos) << a.error().message;
  EXPECT_EQ(a.error().describe().find("TESTSECRET"), std::string::npos);
  EXPECT_NE(a.error().describe().find("Incorrect API key provided: Bearer [redacted]"), std::string::npos)
      << a.error().describe();
  const FaultReport report = backend.faultReport();
  EXPECT_EQ(report.firstError.find("TESTSECRET"), std::string::npos);
  EXPECT_EQ(report.summary().find("TESTSECRET"), std::string::npos);
  // The key was sent (so that the echo is real), only in the header.
  ASSERT_EQ(h.server.requestCount(), 1);
  EXPECT_EQ(h.server.requests()[0].authorization, std::string("Bearer ") + kSecret);
}

TEST(FaultStats, EachFailureKindIsCountedWithTheFirstError) {
  Harness h;
  h.server.push(reply(200, textBody("7")));                                    // no logprobs
  h.server.push(reply(200, "this is not JSON"));                               // malformed
  h.server.push(reply(503, errorBody("overloaded", "server_error", "busy")));  // HTTP status (1 attempt)
  h.server.push(reply(429, errorBody("You exceeded your current quota", "insufficient_quota", "insufficient_quota")));
  h.server.push(reply(404, errorBody("no such model", "invalid_request_error", "model_not_found")));
  TextBackend backend(backendConfig(h), {}, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(model->assess(testBook(), {}).ok());
  const FaultReport r = backend.faultReport();
  EXPECT_EQ(r.backend, "openai");
  EXPECT_EQ(r.ratingFallbackTotal(), 5);
  EXPECT_EQ(r.ratingFallbacks.at("no-logprobs"), 1);
  EXPECT_EQ(r.ratingFallbacks.at("malformed-response"), 1);
  EXPECT_EQ(r.ratingFallbacks.at("http-status"), 2);
  EXPECT_EQ(r.ratingFallbacks.at("quota-exceeded"), 1);
  EXPECT_EQ(r.firstError.rfind("no-logprobs:", 0), 0u) << r.firstError;
  EXPECT_FALSE(r.breakerOpen);  // every one of them was an answer
  const std::string summary = r.summary();
  EXPECT_NE(summary.find("5 ratings fell back"), std::string::npos) << summary;
  EXPECT_NE(summary.find("http-status 2"), std::string::npos) << summary;
  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["rating_fallbacks"], 5);
  EXPECT_EQ(j["rating_fallbacks_by_kind"]["no-logprobs"], 1);
  EXPECT_EQ(j["breaker"]["open"], false);

  backend.resetFaultCounts();
  EXPECT_FALSE(backend.faultReport().any());
}

TEST(FaultStats, LearningFailuresAreCountedApart) {
  Harness h;
  h.server.push(reply(200, textBody("   ")));  // an empty learning reply
  TextBackend backend(backendConfig(h), {}, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  const FeedbackRecord record{testBook(), {}, "I liked it", true};
  EXPECT_FALSE(model->learn(std::span(&record, 1)).ok());
  const FaultReport r = backend.faultReport();
  EXPECT_EQ(r.ratingFallbackTotal(), 0);
  EXPECT_EQ(r.learningFailures.at("malformed-response"), 1);
  EXPECT_NE(r.summary().find("1 learning request failed"), std::string::npos) << r.summary();
}

TEST(FaultStats, TheOfflineBackendReportsNothing) {
  TextBackend backend(TextBackendConfig{});
  EXPECT_FALSE(backend.faultReport().any());
  EXPECT_EQ(backend.faultReport().backend, "offline");
  EXPECT_EQ(backend.faultReport().summary(), "");
  EXPECT_FALSE(runFaults(nullptr).any());
}

TEST(CircuitBreaker, OpensAfterConsecutiveTimeoutsAndStopsCallingTheServer) {
  Harness h;
  h.server.setDefault(h.server.hang());
  std::vector<std::string> notices;
  TextBackend backend(
      backendConfig(h, /*attempts=*/1, /*breaker=*/2, kHangTimeoutMs),
      [&](const std::string& w) { notices.push_back(w); }, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  std::vector<ErrorKind> kinds;
  for (int i = 0; i < 6; ++i) {
    auto a = model->assess(testBook(), {});
    ASSERT_FALSE(a.ok());
    kinds.push_back(a.error().kind);
  }
  EXPECT_EQ(kinds[0], ErrorKind::Timeout);
  EXPECT_EQ(kinds[1], ErrorKind::Timeout);
  for (int i = 2; i < 6; ++i) EXPECT_EQ(kinds[i], ErrorKind::CircuitOpen);
  EXPECT_EQ(h.server.requestCount(), 2);  // nothing after the breaker opened
  ASSERT_EQ(notices.size(), 1u);          // said once
  EXPECT_NE(notices[0].find("circuit breaker open after 2 consecutive server failures"), std::string::npos)
      << notices[0];
  const FaultReport r = backend.faultReport();
  EXPECT_TRUE(r.breakerOpen);
  EXPECT_EQ(r.breakerThreshold, 2);
  EXPECT_EQ(r.ratingFallbacks.at("timeout"), 2);
  EXPECT_EQ(r.ratingFallbacks.at("circuit-open"), 4);
  EXPECT_NE(r.summary().find("circuit breaker open"), std::string::npos);
  // A new trial forgets the counts, not the open breaker.
  backend.resetFaultCounts();
  EXPECT_TRUE(backend.faultReport().breakerOpen);
}

TEST(CircuitBreaker, AnAnswerResetsTheCount) {
  Harness h;
  h.server.push(h.server.hang());
  h.server.push(replyRating({{"6", 1.0}}));
  h.server.push(h.server.hang());
  h.server.push(replyRating({{"6", 1.0}}));
  TextBackend backend(backendConfig(h, 1, 2, kHangTimeoutMs), {}, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  const PromptTemplates prompts = examplePrompts();
  // Different items, so that the response cache does not answer.
  EXPECT_FALSE(model->assess(Item{"A", {}}, {}).ok());
  EXPECT_TRUE(model->assess(Item{"B", {}}, {}).ok());
  EXPECT_FALSE(model->assess(Item{"C", {}}, {}).ok());
  EXPECT_TRUE(model->assess(Item{"D", {}}, {}).ok());
  EXPECT_FALSE(backend.faultReport().breakerOpen);
  EXPECT_EQ(h.server.requestCount(), 4);
}

TEST(CircuitBreaker, ConnectionRefusedCountsAndZeroDisablesIt) {
  CircuitBreaker off(0);
  for (int i = 0; i < 10; ++i) off.recordFailure(Error{ErrorKind::Transport, "refused"});
  EXPECT_FALSE(off.isOpen());
  int notices = 0;
  CircuitBreaker on(3, [&](const std::string&) { ++notices; });
  on.recordFailure(Error{ErrorKind::Transport, "refused"});
  on.recordFailure(Error{ErrorKind::HttpStatus, "answered", "s", 400});  // an answer resets
  on.recordFailure(Error{ErrorKind::Transport, "refused"});
  on.recordFailure(Error{ErrorKind::Timeout, "slow"});
  EXPECT_FALSE(on.isOpen());
  on.recordFailure(Error{ErrorKind::Transport, "refused"});
  on.recordFailure(Error{ErrorKind::Transport, "refused"});
  EXPECT_TRUE(on.isOpen());
  EXPECT_EQ(notices, 1);
}

TEST(CircuitBreaker, ConfigurationValidatesTheThreshold) {
  EXPECT_TRUE(textBackendConfigFromJson({{"breaker_threshold", 0}}).ok());
  EXPECT_EQ(textBackendConfigFromJson({{"breaker_threshold", 7}}).value().breakerThreshold, 7);
  auto bad = textBackendConfigFromJson({{"breaker_threshold", -1}});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("breaker_threshold"), std::string::npos);
  EXPECT_EQ(TextBackendConfig{}.breakerThreshold, 3);
}

TEST(RunReport, NamesTheBackendAndWritesLlmJson) {
  const nlohmann::json offline = textBackendJson(nullptr);
  EXPECT_EQ(offline["backend"], "offline");
  EXPECT_TRUE(offline["base_url"].is_null());
  EXPECT_TRUE(offline["model"].is_null());
  EXPECT_EQ(TextBackend(TextBackendConfig{}).identityJson(), offline);

  Harness h;
  h.server.setDefault(reply(200, textBody("5")));
  TextBackend backend(backendConfig(h), {}, h.sleeper());
  const nlohmann::json online = textBackendJson(&backend);
  EXPECT_EQ(online["backend"], "openai");
  EXPECT_EQ(online["base_url"], h.server.baseUrl());
  EXPECT_EQ(online["model"], "test-model");
  EXPECT_EQ(online["breaker_threshold"], 3);

  beginRunFaults(&backend);
  EXPECT_FALSE(backend.makeModel(examplePrompts())->assess(testBook(), {}).ok());
  ScratchDir dir;
  ASSERT_TRUE(writeLlmReport(dir.path, &backend, runFaults(&backend)).ok());
  std::ifstream in(dir.path / kLlmReportFile);
  const nlohmann::json written = nlohmann::json::parse(in);
  EXPECT_EQ(written["text_backend"]["model"], "test-model");
  EXPECT_EQ(written["faults"]["rating_fallbacks"], 1);
  EXPECT_EQ(written["faults"]["rating_fallbacks_by_kind"]["no-logprobs"], 1);
  EXPECT_TRUE(written["faults"]["first_error"].is_string());
}

TEST(FaultReport, AddSumsTrials) {
  FaultReport total, a, b;
  a.ratingFallbacks["timeout"] = 2;
  a.firstError = "timeout: first";
  b.ratingFallbacks["timeout"] = 1;
  b.ratingFallbacks["circuit-open"] = 5;
  b.breakerOpen = true;
  b.breakerThreshold = 3;
  b.breakerReason = "timeout: last";
  total.add(a);
  total.add(b);
  EXPECT_EQ(total.ratingFallbackTotal(), 8);
  EXPECT_EQ(total.firstError, "timeout: first");
  EXPECT_TRUE(total.breakerOpen);
  EXPECT_EQ(total.breakerReason, "timeout: last");
}

}  // namespace
}  // namespace cbtl::textpref::testing
