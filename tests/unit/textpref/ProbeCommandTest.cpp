// `cbtl llm probe` end to end: the cbtl binary against the loopback server (path given by CBTL_BINARY).
#include "ChatTestServer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace cbtl::textpref::testing {
namespace {

struct CommandRun {
  int exitCode = -1;
  std::string output;
};

CommandRun runCbtl(const std::string& arguments) {
  CommandRun run;
  const std::string command = std::string(CBTL_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) run.output += buffer;
  const int status = ::pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

TEST(LlmProbeCommand, UsableServerExitsZeroAndReportsSplitTen) {
  ChatTestServer server;
  server.push(replyRating({{"4", 0.9}, {"5", 0.1}}));
  server.push(replyRating({{"1", 0.8}, {"9", 0.2}}));  // "10" split by the tokenizer
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
  EXPECT_NE(run.output.find("offline descriptor model"), std::string::npos) << run.output;
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
  const CommandRun run = runCbtl("llm books --rounds 9");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("backend: offline-descriptor-bayes-v1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Liked items: Cosmos, Pride and Prejudice."), std::string::npos) << run.output;
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
    const bool liked = prompt.find("The book: Cosmos") != std::string::npos ||
                       prompt.find("The book: Pride and Prejudice") != std::string::npos;
    res.set_content(ratingBody({{liked ? "10" : "0", 0.9}, {"5", 0.1}}), "application/json");
  });
  const CommandRun run = runCbtl("llm books --backend openai-compatible --base-url " + server.baseUrl() +
                                 " --model test-model --rounds 2 --attempts 1");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("openai-compatible:test-model"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("theta: Liked books so far: Cosmos."), std::string::npos) << run.output;
}

}  // namespace
}  // namespace cbtl::textpref::testing
