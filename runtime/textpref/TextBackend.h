// TextBackend.h — one configured text-preference backend, from which each personalized constraint gets its model.
//
// The runtime reads a TextBackendConfig (from flags or a JSON file), creates one TextBackend per run, and asks it
// for one TextPreferenceModel per constraint generator, passing the generator's prompt templates. With the
// language-model backend all models share one ChatClient and one ResponseCache (owned by the TextBackend, which
// must outlive its models only through the shared pointers it hands out). With the offline backend the prompts are
// ignored and every model is an independent OfflineDescriptorModel.
//
// Faults: the backend owns one FaultStats that all its language models share (every failed rating and learning
// request is counted there, FaultStats.h) and, for the language-model backend, one CircuitBreaker shared by its
// client (CircuitBreaker.h; it opens after `breakerThreshold` consecutive server failures -- no answer, 408, 429
// or 5xx -- and then says so once through the WarningSink) and one RetryBudget (RetryBudget.h; `retryBudget`
// retries and waits per run, reset by resetFaultCounts() when a run starts). All are thread-safe and may be read
// or reset through a const backend. An optional FaultProgress (FaultProgress.h; the caller passes one only for a
// terminal) is told of every failed attempt and of the retry budget being spent.
#pragma once

#include "runtime/textpref/ChatClient.h"
#include "runtime/textpref/CircuitBreaker.h"
#include "runtime/textpref/FaultProgress.h"
#include "runtime/textpref/FaultStats.h"
#include "runtime/textpref/LlmPreferenceModel.h"
#include "runtime/textpref/OfflineDescriptorModel.h"
#include "runtime/textpref/ResponseCache.h"
#include "runtime/textpref/RetryBudget.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

namespace cbtl::textpref {

enum class BackendKind { OfflineDescriptor, OpenAiCompatible };

const char* backendKindName(BackendKind kind);  // "offline-descriptor", "openai-compatible"
std::optional<BackendKind> parseBackendKind(std::string_view name);

struct TextBackendConfig {
  BackendKind kind = BackendKind::OfflineDescriptor;  // the embedded default: no network, no key
  ChatConfig chat;                                    // language-model backend only
  std::filesystem::path cacheDir;                     // empty: memory-only cache
  CacheMode cacheMode = CacheMode::ReadWrite;
  RatingScale scale = RatingScale::Digits;
  bool renormalize = true;
  SplitPolicy split = SplitPolicy::Auto;
  double minCoverage = 0.5;
  int topLogprobs = 20;
  std::int64_t seed = 0;
  int breakerThreshold = 3;       // consecutive server failures that open the circuit breaker; 0 disables it
  RetryBudgetLimits retryBudget;  // retries and requested waits per run (RetryBudget.h)
  OfflineModelOptions offline;
};

// Reads a config object such as
//   {"backend": "openai-compatible", "base_url": "http://127.0.0.1:8080/v1", "model": "qwen2.5",
//    "api_key_env": "OPENAI_API_KEY", "max_tokens_field": "max_tokens", "connect_timeout_ms": 5000,
//    "request_timeout_ms": 60000, "max_attempts": 5, "cache_dir": "cache/llm", "cache_mode": "read-only",
//    "scale": "digits", "renormalize": true, "split": "auto", "min_coverage": 0.5, "top_logprobs": 20, "seed": 0,
//    "breaker_threshold": 3, "retry_budget": 100, "retry_wait_budget_ms": 300000, "max_retry_after_ms": 10000}
// Every key is optional; unknown keys and wrong types are Configuration errors naming the key.
Result<TextBackendConfig> textBackendConfigFromJson(const nlohmann::json& j);

class TextBackend {
 public:
  explicit TextBackend(TextBackendConfig config, WarningSink warn = {}, SleepFunction sleep = realSleep(),
                       std::shared_ptr<FaultProgress> progress = nullptr);

  const TextBackendConfig& config() const { return config_; }
  // A fresh model for one constraint generator. Never null. `scale` overrides the configured rating scale for
  // this model (a `.cbtl` generator declares its own `rating:`); the offline backend has no rating scale.
  std::unique_ptr<TextPreferenceModel> makeModel(const PromptTemplates& prompts,
                                                 std::optional<RatingScale> scale = std::nullopt) const;
  // The language-model judge for simulated users (null with the offline backend).
  std::shared_ptr<LlmPreferenceModel> makeJudge(const PromptTemplates& prompts) const;
  // The shared cache (null with the offline backend).
  const ResponseCache* cache() const { return cache_.get(); }

  // The failures counted so far, with the backend's name ("offline" or "openai") and the breaker's state.
  FaultReport faultReport() const;
  // Forgets the counted failures and refills the retry budget (a new trial starts); an open breaker stays open.
  void resetFaultCounts() const;
  // {"backend": "openai", "base_url", "model", "request_timeout_ms", "max_attempts", "breaker_threshold",
  //  "retry_budget", "retry_wait_budget_ms", "max_retry_after_ms"} for
  // the language-model backend; {"backend": "offline", "base_url": null, "model": null} for the offline one.
  nlohmann::json identityJson() const;

 private:
  LlmModelOptions llmOptions(const PromptTemplates& prompts) const;

  TextBackendConfig config_;
  std::shared_ptr<ResponseCache> cache_;
  std::shared_ptr<ChatClient> client_;
  std::shared_ptr<FaultStats> faults_ = std::make_shared<FaultStats>();
  std::shared_ptr<CircuitBreaker> breaker_;
  std::shared_ptr<RetryBudget> budget_;
};

}  // namespace cbtl::textpref
