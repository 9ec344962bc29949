// `cbtl run`, `cbtl solve` and `cbtl experiment` with a failing language-model server (the Feeding domain, whose
// three text factors ask for ratings): the fallbacks are counted and printed, a silent server opens the circuit
// breaker (said once) instead of stalling the run, and so does a server answering 5xx; llm.json and config.json
// name the backend, and llm.json is there however the run ends (an error, SIGINT, SIGTERM); quoted server
// messages never show the API key, and out-of-range fault options are usage errors naming the option.
// Bounded time is checked by the ctest TIMEOUT, not by assertions.
#include "tests/unit/textpref/ChatTestServer.h"
#include "tests/unit/textpref/CommandRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>

namespace cbtl::textpref::testing {
namespace {

const std::string kFeeding = std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl";
const std::string kShortTrial = " --steps 4 --eval-every 2 --eval-tasks 1 --max-eval-steps 3 --max-iters 50";

struct OutDir {
  std::filesystem::path path;
  OutDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() / ("cbtl-fault-cmd-" + std::to_string(rd()) + std::to_string(rd()));
  }
  ~OutDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  nlohmann::json read(const std::string& file) const {
    std::ifstream in(path / file);
    return nlohmann::json::parse(in, nullptr, false);
  }
};

std::string openai(const ChatTestServer& server) {
  return " --text-backend openai --llm-model test-model --llm-base-url " + server.baseUrl();
}

TEST(LlmFaultsInARun, NoLogprobsFallbacksAreCountedPrintedAndRecorded) {
  ChatTestServer server;
  server.setDefault(reply(200, textBody("7")));
  OutDir out;
  const CommandRun run =
      runCbtl("run " + kFeeding + kShortTrial + openai(server) + " --llm-attempts 1 --out " + out.path.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("fell back to the generator's fallback (no-logprobs"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("first error: no-logprobs:"), std::string::npos) << run.output;
  const nlohmann::json llm = out.read("llm.json");
  ASSERT_TRUE(llm.is_object()) << run.output;
  EXPECT_GT(llm["faults"]["rating_fallbacks"].get<long>(), 0);
  EXPECT_EQ(llm["faults"]["rating_fallbacks"], llm["faults"]["rating_fallbacks_by_kind"]["no-logprobs"]);
  EXPECT_EQ(llm["faults"]["breaker"]["open"], false);
  const nlohmann::json config = out.read("config.json");
  EXPECT_EQ(config["text_backend"]["backend"], "openai");
  EXPECT_EQ(config["text_backend"]["base_url"], server.baseUrl());
  EXPECT_EQ(config["text_backend"]["model"], "test-model");
  EXPECT_EQ(config["text_backend"]["max_attempts"], 1);
}

TEST(LlmFaultsInARun, ASilentServerOpensTheBreakerAndTheRunFinishes) {
  ChatTestServer server;
  server.setDefault(server.hang());
  OutDir out;
  const CommandRun run = runCbtl("run " + kFeeding + kShortTrial + openai(server) +
                                 " --llm-timeout-ms 200 --llm-attempts 1 --llm-breaker 2 --out " + out.path.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(occurrences(run.output, "warning: language model: circuit breaker open"), 1) << run.output;
  EXPECT_NE(run.output.find("circuit breaker open after 2 consecutive server failures"), std::string::npos)
      << run.output;
  EXPECT_EQ(server.requestCount(), 2);  // nothing after the breaker opened
  const nlohmann::json faults = out.read("llm.json")["faults"];
  EXPECT_EQ(faults["breaker"]["open"], true);
  EXPECT_EQ(faults["breaker"]["threshold"], 2);
  EXPECT_EQ(faults["rating_fallbacks_by_kind"]["timeout"], 2);
  EXPECT_GT(faults["rating_fallbacks_by_kind"]["circuit-open"].get<long>(), 0);
}

TEST(LlmFaultsInARun, AServerAnswering500OpensTheBreakerAndBoundsTheRequests) {
  ChatTestServer server;
  server.setDefault(reply(500, errorBody("internal error", "server_error", "")));
  OutDir out;
  const CommandRun run = runCbtl("run " + kFeeding + kShortTrial + openai(server) +
                                 " --llm-attempts 2 --llm-breaker 2 --out " + out.path.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(occurrences(run.output, "warning: language model: circuit breaker open"), 1) << run.output;
  EXPECT_EQ(server.requestCount(), 2 * 2);  // threshold x attempts; the previous binary never stopped
  const nlohmann::json faults = out.read("llm.json")["faults"];
  EXPECT_EQ(faults["breaker"]["open"], true);
  EXPECT_EQ(faults["rating_fallbacks_by_kind"]["http-status"], 2);
  EXPECT_EQ(faults["retries"]["used"], 2);
  // Not a terminal: no live fault lines.
  EXPECT_EQ(run.output.find("retrying in"), std::string::npos) << run.output;
}

TEST(LlmFaultsInARun, ARunStoppedByAnErrorLeavesLlmJson) {
  ChatTestServer server;
  server.setDefault(reply(503, "overloaded"));
  OutDir out;
  // The first checkpoint's write fails: the run stops with an error (exit 1) before its end.
  const CommandRun run =
      runCbtl("run " + kFeeding + kShortTrial + openai(server) + " --llm-attempts 1 --out " + out.path.string(),
              "CBTL_TEST_WRITE_FAILS=checkpoint.json ");
  ASSERT_NE(run.exitCode, 0) << run.output;
  const nlohmann::json llm = out.read("llm.json");
  ASSERT_TRUE(llm.is_object()) << run.output;
  EXPECT_EQ(llm["text_backend"]["backend"], "openai");
  EXPECT_TRUE(llm["faults"]["retries"].is_object()) << llm.dump();
  EXPECT_FALSE(std::filesystem::exists(out.path / "complete.json"));
}

TEST(LlmFaultsInARun, AnInterruptedRunLeavesLlmJson) {
  for (const int signal : {SIGINT, SIGTERM}) {
    ChatTestServer server;
    server.push(reply(500, "down"));
    server.setDefault(server.hang());
    OutDir out;
    const std::filesystem::path pidFile = out.path.string() + ".pid";
    CommandRun run;
    // `exec` keeps the shell's pid, written first, for the signal.
    std::thread cbtl([&] {
      run = runCbtl("run " + kFeeding + kShortTrial + openai(server) +
                        " --llm-attempts 1 --llm-timeout-ms 60000 --out " + out.path.string(),
                    "echo $$ > " + pidFile.string() + "; exec ");
    });
    long pid = 0;
    for (int i = 0; i < 600 && (pid == 0 || server.requestCount() < 2); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      std::ifstream in(pidFile);
      in >> pid;
    }
    ASSERT_GT(pid, 0);
    ASSERT_GE(server.requestCount(), 2);  // the run waits on its second request
    ::kill(static_cast<pid_t>(pid), signal);
    cbtl.join();
    std::filesystem::remove(pidFile);
    EXPECT_EQ(run.exitCode, 128 + signal) << run.output;
    EXPECT_NE(run.output.find("cbtl run: interrupted;"), std::string::npos) << run.output;
    const nlohmann::json llm = out.read("llm.json");
    ASSERT_TRUE(llm.is_object()) << "no llm.json after signal " << signal << "\n" << run.output;
    EXPECT_EQ(llm["faults"]["rating_fallbacks_by_kind"]["http-status"], 1);
  }
}

TEST(LlmFaultsInARun, OfflineRunsRecordTheOfflineBackendAndNoFaults) {
  OutDir out;
  const CommandRun run = runCbtl("run " + kFeeding + kShortTrial + " --out " + out.path.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(run.output.find("language model:"), std::string::npos) << run.output;
  const nlohmann::json config = out.read("config.json");
  EXPECT_EQ(config["text_backend"]["backend"], "offline");
  EXPECT_TRUE(config["text_backend"]["base_url"].is_null());
  EXPECT_TRUE(config["text_backend"]["model"].is_null());
  EXPECT_EQ(out.read("llm.json")["faults"]["rating_fallbacks"], 0);
}

TEST(LlmFaultsInASolve, AnEchoedKeyIsRedactedAndTheFaultsArePrinted) {
  ChatTestServer server;
  server.setDefault(echoAuthorization(401));
  const CommandRun run = runCbtl("solve " + kFeeding + " --max-iters 50" + openai(server) + " --llm-attempts 1",
                                 "OPENAI_API_KEY=sk-proj-SOLVESECRET123456789 ");
  EXPECT_NE(run.output.find("fell back to the generator's fallback (http-status"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Bearer [redacted]"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("SOLVESECRET"), std::string::npos) << run.output;
}

TEST(LlmFaultsInAnExperiment, TheSummaryCountsEveryTrial) {
  ChatTestServer server;
  server.setDefault(reply(200, "not json"));
  const CommandRun run = runCbtl("experiment " + kFeeding + kShortTrial + " --approaches cbtl --seeds 0..2" +
                                 openai(server) + " --llm-attempts 1");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  // One line per trial that asked for ratings on stderr, and the total after the table (which trials ask
  // depends on the episodes the seeds draw; with seeds 0..2 at least two do).
  EXPECT_GE(occurrences(run.output, "fell back to the generator's fallback (malformed-response"), 3) << run.output;
}

TEST(LlmFaultOptions, OutOfRangeValuesAreUsageErrorsNamingTheOption) {
  for (const std::string option :
       {"--llm-attempts 0", "--llm-timeout-ms 0", "--llm-breaker -1", "--llm-attempts 101", "--llm-retry-budget -1",
        "--llm-retry-wait-ms -1", "--llm-max-retry-after-ms 3600001"}) {
    const CommandRun run = runCbtl("run " + kFeeding + " --text-backend openai " + option);
    EXPECT_EQ(run.exitCode, 2) << option << "\n" << run.output;
    EXPECT_NE(run.output.find(option.substr(0, option.find(' '))), std::string::npos) << run.output;
  }
  const CommandRun offline = runCbtl("solve " + kFeeding + " --llm-breaker 2");
  EXPECT_EQ(offline.exitCode, 2) << offline.output;
  EXPECT_NE(offline.output.find("--llm-breaker needs --text-backend openai"), std::string::npos) << offline.output;
}

}  // namespace
}  // namespace cbtl::textpref::testing
