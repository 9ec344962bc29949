#include "runtime/textpref/TextBackend.h"

#include "runtime/textpref/Redaction.h"

#include <fmt/core.h>

#include <set>

namespace cbtl::textpref {

const char* backendKindName(BackendKind kind) {
  return kind == BackendKind::OfflineDescriptor ? "offline-descriptor" : "openai-compatible";
}

std::optional<BackendKind> parseBackendKind(std::string_view name) {
  if (name == "offline-descriptor") return BackendKind::OfflineDescriptor;
  if (name == "openai-compatible") return BackendKind::OpenAiCompatible;
  return std::nullopt;
}

Result<TextBackendConfig> textBackendConfigFromJson(const nlohmann::json& j) {
  auto bad = [](const std::string& what) { return Error{ErrorKind::Configuration, what}; };
  if (!j.is_object()) return bad("the text-backend configuration must be a JSON object");
  static const std::set<std::string> known{"backend",
                                           "base_url",
                                           "model",
                                           "api_key_env",
                                           "max_tokens_field",
                                           "connect_timeout_ms",
                                           "request_timeout_ms",
                                           "max_attempts",
                                           "cache_dir",
                                           "cache_mode",
                                           "scale",
                                           "renormalize",
                                           "split",
                                           "min_coverage",
                                           "top_logprobs",
                                           "seed",
                                           "breaker_threshold",
                                           "retry_budget",
                                           "retry_wait_budget_ms",
                                           "max_retry_after_ms"};
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) return bad(fmt::format("unknown text-backend option \"{}\"", key));

  TextBackendConfig c;
  auto text = [&](const char* key, std::string& out) -> std::optional<Error> {
    if (!j.contains(key)) return std::nullopt;
    if (!j[key].is_string()) return bad(fmt::format("text-backend option \"{}\" must be a string", key));
    out = j[key].get<std::string>();
    return std::nullopt;
  };
  auto integer = [&](const char* key, auto& out, long long lo, long long hi) -> std::optional<Error> {
    if (!j.contains(key)) return std::nullopt;
    if (!j[key].is_number_integer() || j[key].get<long long>() < lo || j[key].get<long long>() > hi)
      return bad(fmt::format("text-backend option \"{}\" must be an integer in {}..{}", key, lo, hi));
    out = static_cast<std::remove_reference_t<decltype(out)>>(j[key].get<long long>());
    return std::nullopt;
  };
  std::string backend = backendKindName(c.kind), cacheDir, cacheMode = cacheModeName(c.cacheMode),
              scale = ratingScaleName(c.scale), split = splitPolicyName(c.split);
  for (auto e :
       {text("backend", backend), text("base_url", c.chat.baseUrl), text("model", c.chat.model),
        text("api_key_env", c.chat.apiKeyEnv), text("max_tokens_field", c.chat.maxTokensField),
        text("cache_dir", cacheDir), text("cache_mode", cacheMode), text("scale", scale), text("split", split),
        integer("connect_timeout_ms", c.chat.connectTimeoutMs, 1, 3600000),
        integer("request_timeout_ms", c.chat.requestTimeoutMs, 1, 3600000),
        integer("max_attempts", c.chat.retry.maxAttempts, 1, 100), integer("top_logprobs", c.topLogprobs, 1, 20),
        integer("seed", c.seed, 0, INT64_MAX), integer("breaker_threshold", c.breakerThreshold, 0, 1000),
        integer("retry_budget", c.retryBudget.retries, 0, 1000000),
        integer("retry_wait_budget_ms", c.retryBudget.waitMs, 0, 86400000),
        integer("max_retry_after_ms", c.chat.retry.maxRetryAfterMs, 0, 3600000)})
    if (e) return *e;
  if (j.contains("renormalize")) {
    if (!j["renormalize"].is_boolean()) return bad("text-backend option \"renormalize\" must be a boolean");
    c.renormalize = j["renormalize"].get<bool>();
  }
  if (j.contains("min_coverage")) {
    if (!j["min_coverage"].is_number() || j["min_coverage"].get<double>() < 0.0 ||
        j["min_coverage"].get<double>() > 1.0)
      return bad("text-backend option \"min_coverage\" must be a number in 0..1");
    c.minCoverage = j["min_coverage"].get<double>();
  }
  auto kind = parseBackendKind(backend);
  if (!kind) return bad(fmt::format("unknown backend \"{}\" (offline-descriptor or openai-compatible)", backend));
  auto mode = parseCacheMode(cacheMode);
  if (!mode) return bad(fmt::format("unknown cache mode \"{}\" (off, read-write, read-only, record)", cacheMode));
  auto sc = parseRatingScale(scale);
  if (!sc) return bad(fmt::format("unknown rating scale \"{}\" (digits or options)", scale));
  auto sp = parseSplitPolicy(split);
  if (!sp) return bad(fmt::format("unknown split policy \"{}\" (auto, always, never)", split));
  c.kind = *kind;
  c.cacheMode = *mode;
  c.cacheDir = cacheDir;
  c.scale = *sc;
  c.split = *sp;
  return c;
}

namespace {
// A client together with the cache it points to, so that a model's shared_ptr<ChatClient> keeps both alive even
// after the TextBackend is gone.
struct ClientWithCache {
  std::shared_ptr<ResponseCache> cache;
  ChatClient client;
  ClientWithCache(std::shared_ptr<ResponseCache> c, const ChatConfig& config, SleepFunction sleep)
      : cache(std::move(c)), client(config, cache.get(), std::move(sleep)) {}
};
}  // namespace

TextBackend::TextBackend(TextBackendConfig config, WarningSink warn, SleepFunction sleep,
                         std::shared_ptr<FaultProgress> progress)
    : config_(std::move(config)) {
  if (config_.kind == BackendKind::OpenAiCompatible) {
    breaker_ = std::make_shared<CircuitBreaker>(config_.breakerThreshold, warn);
    // A spent budget is said on a terminal only: llm.json and the run's summary record it anyway.
    RetryBudget::Notice onSpent;
    if (progress) onSpent = [progress](const std::string& line) { progress->notice(line); };
    budget_ = std::make_shared<RetryBudget>(config_.retryBudget, std::move(onSpent));
    cache_ = std::make_shared<ResponseCache>(config_.cacheDir, config_.cacheMode, std::move(warn));
    auto holder = std::make_shared<ClientWithCache>(cache_, config_.chat, std::move(sleep));
    client_ = std::shared_ptr<ChatClient>(holder, &holder->client);  // aliasing: owns the holder
    client_->setBreaker(breaker_);
    client_->setRetryBudget(budget_);
    client_->setProgress(std::move(progress));
  }
}

void TextBackend::resetFaultCounts() const {
  faults_->reset();
  if (budget_) budget_->reset();
}

FaultReport TextBackend::faultReport() const {
  FaultReport r = faults_->snapshot();
  r.backend = config_.kind == BackendKind::OfflineDescriptor ? "offline" : "openai";
  if (breaker_) {
    r.breakerThreshold = breaker_->threshold();
    r.breakerOpen = breaker_->isOpen();
    r.breakerReason = breaker_->reason();
  }
  if (budget_) {
    const RetryBudgetUse used = budget_->used();
    r.retryBudget = budget_->limits().retries;
    r.retryWaitBudgetMs = budget_->limits().waitMs;
    r.retriesUsed = used.retries;
    r.retryWaitedMs = used.waitedMs;
    r.retryBudgetSpent = used.spent;
  }
  return r;
}

nlohmann::json TextBackend::identityJson() const {
  if (config_.kind == BackendKind::OfflineDescriptor)
    return nlohmann::json{{"backend", "offline"}, {"base_url", nullptr}, {"model", nullptr}};
  return nlohmann::json{{"backend", "openai"},
                        {"base_url", redactSecrets(config_.chat.baseUrl)},
                        {"model", config_.chat.model},
                        {"request_timeout_ms", config_.chat.requestTimeoutMs},
                        {"max_attempts", config_.chat.retry.maxAttempts},
                        {"breaker_threshold", config_.breakerThreshold},
                        {"retry_budget", config_.retryBudget.retries},
                        {"retry_wait_budget_ms", config_.retryBudget.waitMs},
                        {"max_retry_after_ms", config_.chat.retry.maxRetryAfterMs}};
}

LlmModelOptions TextBackend::llmOptions(const PromptTemplates& prompts) const {
  LlmModelOptions o;
  o.prompts = prompts;
  o.scale = config_.scale;
  o.renormalize = config_.renormalize;
  o.split = config_.split;
  o.minCoverage = config_.minCoverage;
  o.topLogprobs = config_.topLogprobs;
  o.seed = config_.seed;
  return o;
}

std::unique_ptr<TextPreferenceModel> TextBackend::makeModel(const PromptTemplates& prompts,
                                                            std::optional<RatingScale> scale) const {
  if (config_.kind == BackendKind::OfflineDescriptor) return std::make_unique<OfflineDescriptorModel>(config_.offline);
  LlmModelOptions options = llmOptions(prompts);
  if (scale) options.scale = *scale;
  return std::make_unique<LlmPreferenceModel>(client_, std::move(options), faults_);
}

std::shared_ptr<LlmPreferenceModel> TextBackend::makeJudge(const PromptTemplates& prompts) const {
  if (config_.kind == BackendKind::OfflineDescriptor) return nullptr;
  return std::make_shared<LlmPreferenceModel>(client_, llmOptions(prompts), faults_);
}

}  // namespace cbtl::textpref
