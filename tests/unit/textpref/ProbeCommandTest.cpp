// `cbtl llm probe` end to end: the cbtl binary against the loopback server (path given by CBTL_BINARY).
#include "tests/unit/textpref/ChatTestServer.h"
#include "tests/unit/textpref/CommandRun.h"

#include <gtest/gtest.h>

#include <string>

namespace cbtl::textpref::testing {
namespace {

TEST(LlmProbeCommand, UsableServerExitsZeroAndReportsSplitTen) {
  ChatTestServer server;
  server.push(replyRating({{"4", 0.9}, {"5", 0.1}}));
  server.push(replyRating({{"1", 0.8}, {"9", 0.2}}));    // "10" split by the tokenizer
  server.push(replyRating({{"0", 0.95}, {".", 0.05}}));  // the pre-filled "1" is continued with "0"
  const CommandRun run = runCbtl("llm probe --base-url " + server.baseUrl() + " --model test-model --attempts 1");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("verdict: usable"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("split"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("continues a pre-filled answer"), std::string::npos) << run.output;
  const auto requests = server.requests();
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_EQ(requests[2].body["messages"][1]["content"], "1");
}

TEST(LlmProbeCommand, ServerWithoutLogprobsExitsOne) {
  ChatTestServer server;
  server.setDefault(reply(200, textBody("4")));
  const CommandRun run = runCbtl("llm probe --base-url " + server.baseUrl() + " --model test-model --attempts 1");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  EXPECT_NE(run.output.find("verdict: unusable: no logprobs:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("offline descriptor model"), std::string::npos) << run.output;
}

// Each failure gets its own verdict, naming it (ProbeVerdict.h).
std::string probeAgainst(ChatTestServer& server, const std::string& environment = {}) {
  const CommandRun run = runCbtl("llm probe --base-url " + server.baseUrl() +
                                     " --model test-model --attempts 1 --timeout-ms 200 --connect-timeout-ms 200",
                                 environment);
  EXPECT_EQ(run.exitCode, 1) << run.output;
  return run.output;
}

TEST(LlmProbeCommand, VerdictNamesAnHttpStatusAndRedactsTheEchoedKey) {
  ChatTestServer server;
  server.setDefault(echoAuthorization(401));
  const std::string out = probeAgainst(server, "OPENAI_API_KEY=sk-proj-PROBESECRET987654321 ");
  EXPECT_NE(out.find("verdict: unusable: HTTP status 401:"), std::string::npos) << out;
  EXPECT_NE(out.find("Check the API key in $OPENAI_API_KEY"), std::string::npos) << out;
  EXPECT_NE(out.find("Bearer [redacted]"), std::string::npos) << out;
  EXPECT_EQ(out.find("PROBESECRET"), std::string::npos) << out;
}

TEST(LlmProbeCommand, VerdictNamesQuotaMalformedRepliesAndLowCoverage) {
  ChatTestServer quota;
  quota.setDefault(
      reply(429, errorBody("You exceeded your current quota", "insufficient_quota", "insufficient_quota")));
  const std::string q = probeAgainst(quota);
  EXPECT_NE(q.find("verdict: unusable: quota exceeded (HTTP 429)"), std::string::npos) << q;

  ChatTestServer garbage;
  garbage.setDefault(reply(200, "<html>not a chat completion</html>"));
  const std::string g = probeAgainst(garbage);
  EXPECT_NE(g.find("verdict: unusable: malformed reply:"), std::string::npos) << g;

  ChatTestServer words;
  words.setDefault(replyRating({{"four", 0.9}, {"Four", 0.1}}));
  const std::string w = probeAgainst(words);
  EXPECT_NE(w.find("verdict: unusable: low coverage:"), std::string::npos) << w;
}

TEST(LlmProbeCommand, VerdictNamesATransportErrorForARefusedOrSilentServer) {
  const CommandRun refused = runCbtl("llm probe --base-url http://127.0.0.1:" + std::to_string(unusedLoopbackPort()) +
                                     "/v1 --model m --attempts 1 --timeout-ms 2000 --connect-timeout-ms 2000");
  EXPECT_EQ(refused.exitCode, 1) << refused.output;
  EXPECT_NE(refused.output.find("verdict: unusable: transport error:"), std::string::npos) << refused.output;

  ChatTestServer silent;
  silent.setDefault(silent.hang());
  const std::string out = probeAgainst(silent);
  EXPECT_NE(out.find("verdict: unusable: transport error:"), std::string::npos) << out;
  EXPECT_NE(out.find("timeout"), std::string::npos) << out;
  EXPECT_NE(out.find("not asked"), std::string::npos) << out;  // one silent question is enough
  EXPECT_EQ(silent.requestCount(), 1);
}

TEST(LlmProbeCommand, BadUrlExitsOneAndMissingOptionExitsTwo) {
  EXPECT_EQ(runCbtl("llm probe --base-url ftp://example --model m").exitCode, 1);
  EXPECT_EQ(runCbtl("llm probe --model m").exitCode, 2);
}

}  // namespace
}  // namespace cbtl::textpref::testing

namespace cbtl::textpref::testing {
namespace {

TEST(LlmBooksCommand, OfflineBackendRunsWithoutAServer) {
  const CommandRun run = runCbtl(std::string("llm books ") + CBTL_DOMAINS_DIR + "/books/books.cbtl --rounds 9");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("backend: offline-descriptor-bayes-v1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Liked items: cosmos, prideAndPrejudice."), std::string::npos) << run.output;
}

TEST(LlmBooksCommand, LanguageModelBackendAgainstTheLoopbackServer) {
  ChatTestServer server;
  server.setDefault([](const httplib::Request& req, httplib::Response& res) {
    const auto body = nlohmann::json::parse(req.body);
    const std::string prompt = body["messages"][0]["content"];
    if (!body.contains("logprobs")) {  // a LearningPrompt
      res.set_content(textBody("Liked books so far: Cosmos."), "application/json");
      return;
    }
    const bool liked = prompt.find("title: Cosmos)") != std::string::npos ||
                       prompt.find("title: Pride and Prejudice)") != std::string::npos;
    res.set_content(ratingBody({{liked ? "10" : "0", 0.9}, {"5", 0.1}}), "application/json");
  });
  const CommandRun run = runCbtl(std::string("llm books ") + CBTL_DOMAINS_DIR + "/books/books.cbtl" +
                                 " --backend openai-compatible --base-url " + server.baseUrl() +
                                 " --model test-model --rounds 2 --attempts 1");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("openai-compatible:test-model"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("theta: Liked books so far: Cosmos."), std::string::npos) << run.output;
}

}  // namespace
}  // namespace cbtl::textpref::testing
