#include "runtime/textpref/ChatClient.h"

#include "runtime/textpref/Redaction.h"

#include <fmt/core.h>

#include <cstdlib>
#include <exception>

namespace cbtl::textpref {
namespace {

// The server's own error message, if the body has the OpenAI error shape; otherwise the start of the body.
std::string serverMessage(const std::string& body) {
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (!j.is_discarded() && j.is_object() && j.contains("error")) {
    const auto& e = j["error"];
    if (e.is_object() && e.contains("message") && e["message"].is_string()) return e["message"].get<std::string>();
    if (e.is_string()) return e.get<std::string>();
  }
  std::string head = body.substr(0, 200);
  for (char& c : head)
    if (c == '\n' || c == '\r') c = ' ';
  return head.empty() ? "(empty body)" : head;
}

}  // namespace

Result<ChatResponse> parseChatResponse(const nlohmann::json& body, const std::string& server) {
  auto malformed = [&](const std::string& what) {
    return Error{ErrorKind::MalformedResponse, fmt::format("response is not a chat completion: {}", what), server};
  };
  if (!body.is_object()) return malformed("the body is not a JSON object");
  if (!body.contains("choices") || !body["choices"].is_array() || body["choices"].empty())
    return malformed("no choices");
  const auto& choice = body["choices"][0];
  if (!choice.is_object() || !choice.contains("message") || !choice["message"].is_object())
    return malformed("choices[0] has no message");
  ChatResponse out;
  const auto& message = choice["message"];
  if (message.contains("content") && message["content"].is_string())
    out.content = message["content"].get<std::string>();
  if (body.contains("system_fingerprint") && body["system_fingerprint"].is_string())
    out.systemFingerprint = body["system_fingerprint"].get<std::string>();
  if (choice.contains("logprobs") && choice["logprobs"].is_object()) {
    const auto& lp = choice["logprobs"];
    if (lp.contains("content") && lp["content"].is_array() && !lp["content"].empty() && lp["content"][0].is_object()) {
      const auto& first = lp["content"][0];
      if (first.contains("top_logprobs") && first["top_logprobs"].is_array()) {
        for (const auto& entry : first["top_logprobs"]) {
          if (!entry.is_object() || !entry.contains("token") || !entry["token"].is_string() ||
              !entry.contains("logprob") || !entry["logprob"].is_number())
            return malformed("a top_logprobs entry lacks token or logprob");
          out.firstTokenTop.push_back({entry["token"].get<std::string>(), entry["logprob"].get<double>()});
        }
        out.hasLogprobs = !out.firstTokenTop.empty();
      }
    }
  }
  return out;
}

ChatClient::ChatClient(ChatConfig config, ResponseCache* cache, SleepFunction sleep)
    : config_(std::move(config)), cache_(cache), sleep_(std::move(sleep)), rng_(config_.jitterSeed) {
  if (!sleep_) sleep_ = realSleep();
}

std::string ChatClient::server() const { return serverOf(config_.baseUrl); }

Result<nlohmann::json> ChatClient::requestBody(const ChatRequest& request) const {
  auto bad = [&](const std::string& what) { return Error{ErrorKind::Configuration, what, server()}; };
  if (config_.model.empty()) return bad("no model name configured");
  if (config_.maxTokensField.empty()) return bad("the max-tokens field name is empty");
  if (request.topLogprobs < 0 || request.topLogprobs > 20)
    return bad(fmt::format("top_logprobs must be within 0..20, got {}", request.topLogprobs));
  if (request.maxTokens < 1) return bad("max tokens must be at least 1");
  if (request.messages.empty()) return bad("a chat request needs at least one message");
  nlohmann::json messages = nlohmann::json::array();
  for (const auto& m : request.messages) messages.push_back({{"role", m.role}, {"content", m.content}});
  nlohmann::json body{{"model", config_.model},
                      {"messages", std::move(messages)},
                      {"temperature", request.temperature},
                      {"n", 1},
                      {config_.maxTokensField, request.maxTokens}};
  if (request.seed) body["seed"] = *request.seed;
  if (request.topLogprobs > 0) {
    body["logprobs"] = true;
    body["top_logprobs"] = request.topLogprobs;
  }
  if (!request.extraBody.is_null()) {
    if (!request.extraBody.is_object()) return bad("extra request fields must be a JSON object");
    for (const auto& [key, value] : request.extraBody.items()) {
      if (body.contains(key) || key == "logprobs" || key == "top_logprobs" || key == "seed")
        return bad(fmt::format("extra request field \"{}\" would override a field the client sets", key));
      body[key] = value;
    }
  }
  return body;
}

Result<ChatResponse> ChatClient::complete(const ChatRequest& request) {
  auto result = completeUnredacted(request);
  if (result) return result;
  Error e = result.error();
  e.message = redactSecrets(e.message, secretFromEnvironment(config_.apiKeyEnv));
  return e;
}

Result<ChatResponse> ChatClient::completeUnredacted(const ChatRequest& request) {
  try {
    auto body = requestBody(request);
    if (!body) return body.error();
    if (cache_ != nullptr) {
      if (auto cached = cache_->lookup(body.value())) {
        auto parsed = parseChatResponse(*cached, server());
        if (parsed) {
          parsed.value().fromCache = true;
          parsed.value().raw = std::move(*cached);
          return parsed;
        }
      }
      if (cache_->mode() == CacheMode::ReadOnly) {
        return Error{ErrorKind::CacheMiss,
                     fmt::format("read-only response cache has no entry {} (model {}); the network is not used",
                                 ResponseCache::keyOf(body.value()), config_.model),
                     server()};
      }
    }
    if (breaker_ && breaker_->isOpen()) return breaker_->openError(server());
    auto response = send(body.value());
    if (breaker_) {
      if (response)
        breaker_->recordAnswer();
      else
        breaker_->recordFailure(response.error());
    }
    if (response && cache_ != nullptr && (request.topLogprobs == 0 || response.value().hasLogprobs)) {
      // Store the raw JSON so replays parse exactly what the server said.
      cache_->store(body.value(), response.value().raw);
    }
    return response;
  } catch (const std::exception& e) {
    return Error{ErrorKind::Transport, fmt::format("unexpected failure: {}", e.what()), server()};
  }
}

Result<ChatResponse> ChatClient::parseAnswer(const HttpResponse& r, int attempt) const {
  const int status = static_cast<int>(r.status);
  nlohmann::json raw = nlohmann::json::parse(r.body, nullptr, /*allow_exceptions=*/false);
  if (raw.is_discarded())
    return Error{ErrorKind::MalformedResponse, "response body is not valid JSON", server(), status, attempt};
  auto parsed = parseChatResponse(raw, server());
  if (!parsed) {
    Error e = parsed.error();
    e.httpStatus = status;
    e.attempts = attempt;
    return e;
  }
  parsed.value().attempts = attempt;
  parsed.value().raw = std::move(raw);
  return parsed;
}

Result<ChatResponse> ChatClient::send(const nlohmann::json& body) {
  HttpRequest http;
  std::string base = config_.baseUrl;
  while (!base.empty() && base.back() == '/') base.pop_back();
  http.url = base + "/chat/completions";
  http.body = canonicalJson(body);
  http.connectTimeoutMs = config_.connectTimeoutMs;
  http.totalTimeoutMs = config_.requestTimeoutMs;
  if (!config_.apiKeyEnv.empty()) {
    const char* key = std::getenv(config_.apiKeyEnv.c_str());
    if (key != nullptr && *key != '\0') http.headers.push_back(std::string("Authorization: Bearer ") + key);
  }
  const int maxAttempts = std::max(1, config_.retry.maxAttempts);
  for (int attempt = 1;; ++attempt) {
    auto result = httpPost(http);
    const bool last = attempt >= maxAttempts;
    if (!result) {
      Error e = result.error();
      e.attempts = attempt;
      const bool retried = !last && config_.retry.retryTransportErrors;
      const auto wait = retryWait(fmt::format("failed ({})", errorKindName(e.kind)), !retried,
                                  retried ? backoffDelayMs(attempt - 1, config_.retry, rng_) : 0);
      if (!wait) return e;
      sleep_(std::chrono::milliseconds(*wait));
      continue;
    }
    const HttpResponse& r = result.value();
    const int status = static_cast<int>(r.status);
    switch (classifyResponse(r)) {
      case RetryDecision::Done:
        return parseAnswer(r, attempt);
      case RetryDecision::Quota:
        if (progress_) progress_->attemptFailed(server(), "has no quota left (HTTP 429)", std::nullopt);
        return Error{ErrorKind::QuotaExceeded, fmt::format("quota exhausted (not retried): {}", serverMessage(r.body)),
                     server(), status, attempt};
      case RetryDecision::Fail:
        if (progress_) progress_->attemptFailed(server(), fmt::format("answered HTTP {}", status), std::nullopt);
        return Error{ErrorKind::HttpStatus, serverMessage(r.body), server(), status, attempt};
      case RetryDecision::Retry: {
        // The server's own wait, capped by maxRetryAfterMs, before our backoff (the RNG is drawn only without it,
        // as before, so runs that never see Retry-After keep their jitter sequence).
        const auto asked = last ? std::optional<long>{} : retryAfterMs(r, config_.retry);
        const long wanted = last ? 0 : asked ? *asked : backoffDelayMs(attempt - 1, config_.retry, rng_);
        const auto wait = retryWait(fmt::format("answered HTTP {}", status), last, wanted);
        if (!wait)
          return Error{
              ErrorKind::HttpStatus,
              fmt::format("giving up{}: {}", last ? "" : " (the run's retry budget is spent)", serverMessage(r.body)),
              server(), status, attempt};
        sleep_(std::chrono::milliseconds(*wait));
        break;
      }
    }
  }
}

std::optional<long> ChatClient::retryWait(const std::string& what, bool last, long wantedMs) {
  std::optional<long> wait;
  if (!last && (!budget_ || budget_->take(wantedMs) == RetryGrant::Granted)) wait = wantedMs;
  if (progress_) progress_->attemptFailed(server(), what, wait);
  return wait;
}

}  // namespace cbtl::textpref
