// Bounded language-model faults (issue 42, item 12): a server answering 5xx or 429 opens the circuit breaker as a
// dead one does, a run's retries and waits come from one budget, Retry-After is capped, a person at a terminal
// sees the faults as they happen, and llm.json is written however a run ends. Servers are in-process on
// 127.0.0.1; waits go through a recording sleep function and time through a fake clock, so no test waits or
// asserts a duration.
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/CircuitBreaker.h"
#include "runtime/textpref/FaultProgress.h"
#include "runtime/textpref/RetryBudget.h"
#include "runtime/textpref/RunReport.h"
#include "runtime/textpref/TextBackend.h"

#include <fstream>
#include <numeric>
#include <stdexcept>

namespace cbtl::textpref::testing {
namespace {

// A language-model backend aimed at the loopback server; `extra` overrides or adds options.
TextBackendConfig backendConfig(Harness& h, const nlohmann::json& extra) {
  nlohmann::json j{{"backend", "openai-compatible"}, {"base_url", h.server.baseUrl()}, {"model", "test-model"},
                   {"api_key_env", kKeyVariable},    {"connect_timeout_ms", 1000},     {"request_timeout_ms", 10000}};
  j.update(extra);
  auto config = textBackendConfigFromJson(j);
  EXPECT_TRUE(config.ok()) << config.error().describe();
  return config.value();
}

// Different items, so that the response cache never answers.
Item item(int i) { return Item{"Book " + std::to_string(i), {}}; }

long total(const std::vector<long>& waits) { return std::accumulate(waits.begin(), waits.end(), 0L); }

TEST(BreakerCountsServerErrors, AServerAnswering500OpensItAfterTheThreshold) {
  Harness h;
  h.server.setDefault(reply(500, errorBody("internal error", "server_error", "")));
  std::vector<std::string> notices;
  TextBackend backend(
      backendConfig(h, {{"max_attempts", 3}, {"breaker_threshold", 2}}),
      [&](const std::string& w) { notices.push_back(w); }, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  std::vector<ErrorKind> kinds;
  for (int i = 0; i < 6; ++i) kinds.push_back(model->assess(item(i), {}).error().kind);
  EXPECT_EQ(kinds[0], ErrorKind::HttpStatus);
  EXPECT_EQ(kinds[1], ErrorKind::HttpStatus);
  for (int i = 2; i < 6; ++i) EXPECT_EQ(kinds[i], ErrorKind::CircuitOpen) << i;
  // threshold x attempts requests, then none: the previous code sent all 6 x 3.
  EXPECT_EQ(h.server.requestCount(), 2 * 3);
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_NE(notices[0].find("circuit breaker open after 2 consecutive server failures"), std::string::npos)
      << notices[0];
  EXPECT_NE(notices[0].find("HTTP 500"), std::string::npos) << notices[0];
  EXPECT_TRUE(backend.faultReport().breakerOpen);
}

TEST(BreakerCountsServerErrors, RateLimitsAndQuotaCountOtherClientErrorsDoNot) {
  for (const int status : {429, 500, 502, 503, 408}) {
    CircuitBreaker breaker(3);
    for (int i = 0; i < 3; ++i) breaker.recordFailure(Error{ErrorKind::HttpStatus, "giving up", "s", status, 5});
    EXPECT_TRUE(breaker.isOpen()) << status;
  }
  CircuitBreaker quota(2);
  quota.recordFailure(Error{ErrorKind::QuotaExceeded, "quota", "s", 429, 1});
  quota.recordFailure(Error{ErrorKind::QuotaExceeded, "quota", "s", 429, 1});
  EXPECT_TRUE(quota.isOpen());
  // 400, 401, 404, 422: the server answers; the request or the configuration is wrong. They reset the count.
  CircuitBreaker clientErrors(2);
  for (const int status : {400, 401, 403, 404, 409, 422})
    for (int i = 0; i < 3; ++i) clientErrors.recordFailure(Error{ErrorKind::HttpStatus, "bad", "s", status, 1});
  EXPECT_FALSE(clientErrors.isOpen());
  clientErrors.recordFailure(Error{ErrorKind::HttpStatus, "giving up", "s", 503, 5});
  clientErrors.recordFailure(Error{ErrorKind::HttpStatus, "bad", "s", 400, 1});
  clientErrors.recordFailure(Error{ErrorKind::HttpStatus, "giving up", "s", 503, 5});
  EXPECT_FALSE(clientErrors.isOpen());
  for (const auto kind : {ErrorKind::MalformedResponse, ErrorKind::NoLogprobs, ErrorKind::CacheMiss})
    EXPECT_EQ(classifyForBreaker(Error{kind, "x"}), BreakerOutcome::Answered);
}

TEST(BreakerCountsServerErrors, AServerThatAlwaysRateLimitsOpensIt) {
  Harness h;
  h.server.setDefault(
      reply(429, errorBody("Rate limit reached", "requests", "rate_limit_exceeded"), {{"Retry-After", "30"}}));
  TextBackend backend(backendConfig(h, {{"max_attempts", 5}, {"breaker_threshold", 3}}), {}, h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(model->assess(item(i), {}).ok());
  EXPECT_EQ(h.server.requestCount(), 3 * 5);
  // 3 requests x 4 retries, each capped at 10 s instead of the 30 s asked: 120 s instead of 6 minutes per
  // breaker, and never more than the wait budget.
  EXPECT_EQ(h.sleeps, std::vector<long>(12, 10000));
  EXPECT_TRUE(backend.faultReport().breakerOpen);
}

TEST(RetryAfterCap, ThirtySecondsAskedIsTenSecondsWaited) {
  Harness h;
  h.server.push(reply(429, errorBody("slow down", "requests", "rate_limit_exceeded"), {{"Retry-After", "30"}}));
  h.server.push(replyRating({{"6", 1.0}}));
  LlmPreferenceModel model(h.client(), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  EXPECT_EQ(h.sleeps, std::vector<long>{10000});
  EXPECT_EQ(RetryPolicy{}.maxRetryAfterMs, 10000);
}

TEST(RetryAfterCap, TheCapIsAnOption) {
  Harness h;
  h.server.push(reply(429, errorBody("slow down", "requests", "rate_limit_exceeded"), {{"Retry-After", "30"}}));
  h.server.push(replyRating({{"6", 1.0}}));
  TextBackend backend(backendConfig(h, {{"max_retry_after_ms", 2500}}), {}, h.sleeper());
  ASSERT_TRUE(backend.makeModel(examplePrompts())->assess(testBook(), {}).ok());
  EXPECT_EQ(h.sleeps, std::vector<long>{2500});
  EXPECT_EQ(backend.identityJson()["max_retry_after_ms"], 2500);
}

TEST(RetryBudgetPerRun, OnceSpentNoRequestIsRetriedUntilTheNextRun) {
  Harness h;
  h.server.setDefault(reply(503, errorBody("overloaded", "server_error", "server_is_overloaded")));
  // The breaker is off so that only the budget bounds the retries.
  TextBackend backend(backendConfig(h, {{"max_attempts", 5}, {"breaker_threshold", 0}, {"retry_budget", 3}}), {},
                      h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  beginRunFaults(&backend);
  const Error first = model->assess(item(0), {}).error();
  EXPECT_EQ(first.attempts, 4);  // 1 + the 3 retries of the budget; the 4th retry is refused
  EXPECT_NE(first.message.find("retry budget is spent"), std::string::npos) << first.message;
  EXPECT_EQ(model->assess(item(1), {}).error().attempts, 1);
  EXPECT_EQ(model->assess(item(2), {}).error().attempts, 1);
  EXPECT_EQ(h.server.requestCount(), 4 + 1 + 1);  // the previous code sent 3 x 5
  EXPECT_EQ(h.sleeps.size(), 3u);
  FaultReport r = runFaults(&backend);
  EXPECT_TRUE(r.retryBudgetSpent);
  EXPECT_EQ(r.retriesUsed, 3);
  EXPECT_EQ(r.retryBudget, 3);
  EXPECT_EQ(r.retryWaitedMs, total(h.sleeps));
  EXPECT_NE(r.summary().find("retry budget spent (3 retries"), std::string::npos) << r.summary();
  EXPECT_EQ(r.toJson()["retries"]["spent"], true);
  EXPECT_EQ(r.toJson()["retries"]["used"], 3);
  // The next run has its whole budget again.
  beginRunFaults(&backend);
  EXPECT_EQ(model->assess(item(3), {}).error().attempts, 4);
  EXPECT_EQ(runFaults(&backend).retriesUsed, 3);
}

TEST(RetryBudgetPerRun, TheWaitBudgetBoundsTheTotalSleep) {
  Harness h;
  h.server.setDefault(reply(429, errorBody("slow down", "requests", "rate_limit_exceeded"), {{"Retry-After", "30"}}));
  TextBackend backend(
      backendConfig(h, {{"max_attempts", 5}, {"breaker_threshold", 0}, {"retry_wait_budget_ms", 25000}}), {},
      h.sleeper());
  auto model = backend.makeModel(examplePrompts());
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(model->assess(item(i), {}).ok());
  // Two capped waits fit in 25 s, a third would not: then no retry at all.
  EXPECT_EQ(h.sleeps, (std::vector<long>{10000, 10000}));
  EXPECT_EQ(h.server.requestCount(), 3 + 1 + 1 + 1);
  EXPECT_TRUE(backend.faultReport().retryBudgetSpent);
  EXPECT_EQ(backend.faultReport().retryWaitedMs, 20000);
}

TEST(RetryBudgetPerRun, CountsAreExactAndTheFirstRefusalIsSaidOnce) {
  std::vector<std::string> notices;
  RetryBudget budget({2, 1000}, [&](const std::string& n) { notices.push_back(n); });
  EXPECT_EQ(budget.take(400), RetryGrant::Granted);
  EXPECT_EQ(budget.take(700), RetryGrant::WaitSpent);   // 400 + 700 > 1000
  EXPECT_EQ(budget.take(0), RetryGrant::RetriesSpent);  // spent for good, although one retry remains
  EXPECT_EQ(budget.used().retries, 1);
  EXPECT_EQ(budget.used().waitedMs, 400);
  EXPECT_EQ(notices.size(), 1u);
  budget.reset();
  EXPECT_EQ(budget.take(1000), RetryGrant::Granted);
  EXPECT_EQ(budget.take(0), RetryGrant::Granted);
  EXPECT_EQ(budget.take(0), RetryGrant::RetriesSpent);
  EXPECT_EQ(notices.size(), 2u);
  EXPECT_EQ(TextBackendConfig{}.retryBudget.retries, 100);
  EXPECT_EQ(TextBackendConfig{}.retryBudget.waitMs, 300000);
  for (const char* key : {"retry_budget", "retry_wait_budget_ms", "max_retry_after_ms"}) {
    auto bad = textBackendConfigFromJson({{key, -1}});
    ASSERT_FALSE(bad.ok()) << key;
    EXPECT_NE(bad.error().message.find(key), std::string::npos);
  }
}

// A clock the test moves by hand.
struct FakeClock {
  std::chrono::steady_clock::time_point now{};
  FaultProgress::Clock clock() {
    return [this] { return now; };
  }
};

TEST(FaultProgressLines, FirstFaultAtOnceThenAtMostOneLinePerInterval) {
  FakeClock t;
  std::vector<std::string> lines;
  FaultProgress progress([&](const std::string& l) { lines.push_back(l); }, std::chrono::seconds(5), t.clock());
  progress.attemptFailed("127.0.0.1:9", "answered HTTP 503", 400L);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0],
            "language model: 127.0.0.1:9 answered HTTP 503; retrying in 0.4 s (1 failed attempt so far, 1 retry, "
            "0.4 s of waits)");
  t.now += std::chrono::seconds(1);
  progress.attemptFailed("127.0.0.1:9", "answered HTTP 503", 800L);
  progress.attemptFailed("127.0.0.1:9", "timeout", std::nullopt);
  EXPECT_EQ(lines.size(), 1u);  // within 5 s of the last line
  t.now += std::chrono::seconds(4);
  progress.attemptFailed("127.0.0.1:9", "answered HTTP 429", 10000L);
  ASSERT_EQ(lines.size(), 2u);  // the totals include the attempts not printed
  EXPECT_EQ(lines[1],
            "language model: 127.0.0.1:9 answered HTTP 429; retrying in 10.0 s (4 failed attempts so far, 3 retries, "
            "11.2 s of waits)");
  progress.notice("language model: retry budget spent");
  EXPECT_EQ(lines.size(), 3u);  // notices are never held back
}

TEST(FaultProgressLines, TheBackendReportsRetriesAndTheSpentBudget) {
  Harness h;
  h.server.setDefault(reply(503, errorBody("overloaded", "server_error", "server_is_overloaded")));
  FakeClock t;
  std::vector<std::string> lines;
  auto progress = std::make_shared<FaultProgress>([&](const std::string& l) { lines.push_back(l); },
                                                  std::chrono::seconds(5), t.clock());
  std::vector<std::string> warnings;
  TextBackend backend(
      backendConfig(h, {{"max_attempts", 3}, {"breaker_threshold", 2}, {"retry_budget", 1}}),
      [&](const std::string& w) { warnings.push_back(w); }, h.sleeper(), progress);
  auto model = backend.makeModel(examplePrompts());
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(model->assess(item(i), {}).ok());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("answered HTTP 503; retrying in"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("retry budget spent (1 of 1 retries"), std::string::npos) << lines[1];
  // The breaker's notice goes to the warning sink, terminal or not.
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("circuit breaker open after 2"), std::string::npos);
  EXPECT_EQ(h.server.requestCount(), 2 + 1);
}

nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(LlmJsonOnEveryExit, AnExceptionLeavingTheRunStillWritesIt) {
  Harness h;
  h.server.setDefault(reply(500, "down"));
  TextBackend backend(backendConfig(h, {{"max_attempts", 1}}), {}, h.sleeper());
  ScratchDir dir;
  beginRunFaults(&backend);
  try {
    LlmReportGuard guard(dir.path, &backend);
    EXPECT_FALSE(backend.makeModel(examplePrompts())->assess(testBook(), {}).ok());
    throw std::runtime_error("the simulator failed");
  } catch (const std::runtime_error&) {}
  const nlohmann::json written = readJson(dir.path / kLlmReportFile);
  ASSERT_TRUE(written.is_object());
  EXPECT_EQ(written["faults"]["rating_fallbacks_by_kind"]["http-status"], 1);
  EXPECT_EQ(written["text_backend"]["backend"], "openai");
}

TEST(LlmJsonOnEveryExit, LiveRunsAreWrittenOnDemandAndAFinishedRunIsLeftAlone) {
  ScratchDir a, b;
  {
    LlmReportGuard first(a.path, nullptr);
    auto second = std::make_unique<LlmReportGuard>(b.path, nullptr);
    EXPECT_EQ(writeLiveLlmReports(), 2);  // what an interrupt does
    EXPECT_TRUE(readJson(b.path / kLlmReportFile).is_object());
    std::filesystem::remove(b.path / kLlmReportFile);
    second->finish();
    second.reset();
    EXPECT_FALSE(std::filesystem::exists(b.path / kLlmReportFile));  // finished: its own write was the last
    EXPECT_EQ(writeLiveLlmReports(), 1);
    first.finish();
  }
  EXPECT_EQ(writeLiveLlmReports(), 0);
  EXPECT_EQ(readJson(a.path / kLlmReportFile)["text_backend"]["backend"], "offline");
}

}  // namespace
}  // namespace cbtl::textpref::testing
