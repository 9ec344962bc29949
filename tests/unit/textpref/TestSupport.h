// TestSupport.h — shared set-up of the text-preference tests: a client aimed at the loopback server with a
// recording sleep function, and a scratch folder.
#pragma once

#include "tests/unit/textpref/ChatTestServer.h"

#include "runtime/textpref/ChatClient.h"
#include "runtime/textpref/LlmPreferenceModel.h"
#include "runtime/textpref/Prompts.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace cbtl::textpref::testing {

inline constexpr const char* kKeyVariable = "CBTL_TEXTPREF_TEST_KEY";

struct Harness {
  ChatTestServer server;
  std::vector<long> sleeps;  // requested waits in milliseconds; nothing actually sleeps

  ChatConfig config() {
    ChatConfig c;
    c.baseUrl = server.baseUrl();
    c.model = "test-model";
    c.apiKeyEnv = kKeyVariable;
    c.connectTimeoutMs = 1000;
    c.requestTimeoutMs = 2000;
    c.retry.maxAttempts = 4;
    c.retry.baseDelayMs = 100;
    c.retry.maxDelayMs = 400;
    c.jitterSeed = 7;
    return c;
  }
  SleepFunction sleeper() {
    return [this](std::chrono::milliseconds d) { sleeps.push_back(static_cast<long>(d.count())); };
  }
  std::shared_ptr<ChatClient> client(ResponseCache* cache = nullptr) {
    return std::make_shared<ChatClient>(config(), cache, sleeper());
  }
  std::shared_ptr<ChatClient> client(const ChatConfig& c, ResponseCache* cache = nullptr) {
    return std::make_shared<ChatClient>(c, cache, sleeper());
  }
};

// The engine's generic framing of an example question (what a `.cbtl` generator's `model text(...)` supplies).
inline PromptTemplates examplePrompts() {
  return generatorPrompts("How much would the user enjoy reading this book?",
                          "From the user's reactions, describe which books they like and which they dislike.");
}

inline LlmModelOptions bookOptions() {
  LlmModelOptions o;
  o.prompts = examplePrompts();
  o.seed = 3;
  return o;
}

inline Item testBook() { return Item{"Cosmos", {{"author", {"Carl Sagan"}}, {"genre", {"nonfiction"}}}}; }

// A fresh, empty folder under the system temporary directory, removed by the destructor.
struct ScratchDir {
  std::filesystem::path path;
  ScratchDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() /
           ("cbtl-textpref-test-" + std::to_string(rd()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace cbtl::textpref::testing
