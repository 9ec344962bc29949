// ChatClient.h — an OpenAI-compatible chat-completions client (OpenAI, llama.cpp's server, Ollama >= 0.12.11,
// vLLM), with retries and the response cache.
//
// POST {baseUrl}/chat/completions with a JSON body holding model, messages, temperature, n = 1, the max-tokens
// field (name configurable: "max_tokens" or "max_completion_tokens"), seed, and, when topLogprobs > 0,
// logprobs = true and top_logprobs. The API key is read from the environment variable named by
// ChatConfig::apiKeyEnv at each request and sent only as an Authorization header: it is never part of the
// request body, so it never reaches the cache, an error message or a log line. If the variable is unset or
// empty no Authorization header is sent (local servers need none; OpenAI then answers 401). A server that echoes
// the key back is quoted only after redactSecrets() (Redaction.h): every Error this client returns is redacted.
// Circuit breaker (optional, shared, setBreaker): while it is open, a request the cache cannot answer is a
// CircuitOpen error and the network is not used; each request's outcome (after its retries) is reported to it.
// Retry budget (optional, shared, setRetryBudget): every retry, and the wait before it, is taken from the run's
// budget (RetryBudget.h); once it is spent a failed attempt is the request's last. Without one, only
// RetryPolicy::maxAttempts bounds the retries. Fault progress (optional, shared, setProgress): every failed
// attempt is reported to it (FaultProgress.h), for the live lines on a terminal.
//
// A client is used from one thread at a time (its backoff RNG is not shared); make one client per thread.
// Cache (optional, not owned, must outlive the client): looked up before the network; in ReadOnly mode a miss is
// a CacheMiss error and the network is never reached. Only parsed, usable 2xx responses are stored.
#pragma once

#include "runtime/textpref/CircuitBreaker.h"
#include "runtime/textpref/FaultProgress.h"
#include "runtime/textpref/ResponseCache.h"
#include "runtime/textpref/Result.h"
#include "runtime/textpref/RetryBudget.h"
#include "runtime/textpref/RetryPolicy.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace cbtl::textpref {

struct ChatConfig {
  std::string baseUrl = "https://api.openai.com/v1";  // without the trailing /chat/completions
  std::string model = "gpt-4o-mini";
  std::string apiKeyEnv = "OPENAI_API_KEY";  // name of the variable, never its value
  std::string maxTokensField = "max_tokens";
  long connectTimeoutMs = 5000;
  long requestTimeoutMs = 60000;
  RetryPolicy retry;
  std::uint64_t jitterSeed = 0;  // seeds the backoff-jitter RNG
};

struct ChatMessage {
  std::string role;  // "system", "user" or "assistant"
  std::string content;
};

struct ChatRequest {
  std::vector<ChatMessage> messages;
  int maxTokens = 1;
  double temperature = 0.0;
  std::optional<std::int64_t> seed = 0;
  int topLogprobs = 20;  // 0..20; 0 asks for no log-probabilities
  // Server-specific fields added to the body, e.g. vLLM's {"continue_final_message": true,
  // "add_generation_prompt": false} for a pre-filled assistant turn. Must be an object (or null) whose keys do
  // not clash with the fields above; otherwise the request is a Configuration error.
  nlohmann::json extraBody;
};

struct TokenLogprob {
  std::string token;
  double logprob = 0.0;
};

struct ChatResponse {
  std::string content;                      // choices[0].message.content ("" when null)
  bool hasLogprobs = false;                 // choices[0].logprobs.content[0].top_logprobs was present
  std::vector<TokenLogprob> firstTokenTop;  // top_logprobs of the first generated token
  std::string systemFingerprint;
  bool fromCache = false;
  int attempts = 0;    // HTTP attempts made (0 for a cache hit)
  nlohmann::json raw;  // the whole response body as received (or as cached)
};

// Parses a chat-completions response body. MalformedResponse when it lacks choices[0].message.
Result<ChatResponse> parseChatResponse(const nlohmann::json& body, const std::string& server);

class ChatClient {
 public:
  explicit ChatClient(ChatConfig config, ResponseCache* cache = nullptr, SleepFunction sleep = realSleep());

  const ChatConfig& config() const { return config_; }
  // "host:port" of the configured server.
  std::string server() const;

  // The request body that is sent (and hashed for the cache); Configuration error for invalid options.
  Result<nlohmann::json> requestBody(const ChatRequest& request) const;

  // Sends the request (or answers from the cache). Never throws. Errors are redacted (Redaction.h).
  Result<ChatResponse> complete(const ChatRequest& request);

  // Shares a circuit breaker (null: none). Set before the first request.
  void setBreaker(std::shared_ptr<CircuitBreaker> breaker) { breaker_ = std::move(breaker); }
  // Shares the run's retry budget (null: none). Set before the first request.
  void setRetryBudget(std::shared_ptr<RetryBudget> budget) { budget_ = std::move(budget); }
  // Shares a progress reporter (null: none). Set before the first request.
  void setProgress(std::shared_ptr<FaultProgress> progress) { progress_ = std::move(progress); }

 private:
  Result<ChatResponse> completeUnredacted(const ChatRequest& request);
  Result<ChatResponse> send(const nlohmann::json& body);
  // A 2xx answer of attempt `attempt`, parsed (MalformedResponse when it is not a chat completion).
  Result<ChatResponse> parseAnswer(const HttpResponse& response, int attempt) const;
  // After a failed attempt (`what` for the progress line): the wait before the next attempt, or nullopt when the
  // request gives up (this was its last attempt, or the run's retry budget refused the retry).
  std::optional<long> retryWait(const std::string& what, bool last, long wantedMs);

  ChatConfig config_;
  ResponseCache* cache_;
  SleepFunction sleep_;
  std::mt19937_64 rng_;
  std::shared_ptr<CircuitBreaker> breaker_;
  std::shared_ptr<RetryBudget> budget_;
  std::shared_ptr<FaultProgress> progress_;
};

}  // namespace cbtl::textpref
