#include "runtime/textpref/LlmPreferenceModel.h"

#include "runtime/textpref/Redaction.h"

#include <fmt/core.h>

#include <cctype>

namespace cbtl::textpref {
namespace {

constexpr int kStateFormat = 1;

std::string trimmed(const std::string& s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

}  // namespace

LlmModelOptions referenceParityOptions(PromptTemplates prompts) {
  LlmModelOptions o;
  o.prompts = std::move(prompts);
  o.scale = RatingScale::NumberedOptions;
  o.renormalize = false;
  o.minCoverage = 0.0;
  o.topLogprobs = 11;
  return o;
}

LlmPreferenceModel::LlmPreferenceModel(std::shared_ptr<ChatClient> client, LlmModelOptions options,
                                       std::shared_ptr<FaultStats> faults)
    : client_(std::move(client)),
      faults_(std::move(faults)),
      options_(std::move(options)),
      theta_(options_.prompts.initialTheta) {}

Result<Assessment> LlmPreferenceModel::assess(const Item& item, const Context& context) {
  return assessWithTheta(item, context, theta_);
}

Result<Assessment> LlmPreferenceModel::assessWithTheta(const Item& item, const Context& context,
                                                       const std::string& theta) {
  auto result = rate(item, context, theta);
  if (!result && faults_) faults_->recordRatingFailure(result.error());
  return result;
}

Result<Assessment> LlmPreferenceModel::rate(const Item& item, const Context& context, const std::string& theta) {
  if (!client_) return Error{ErrorKind::Configuration, "the language-model backend has no chat client"};
  const std::string server = client_->server();
  if (options_.topLogprobs < 1)
    return Error{ErrorKind::Configuration, "rating queries need top_logprobs of at least 1", server};
  ChatRequest request;
  request.messages = {{"user", renderConstraintPrompt(options_.prompts, item, context, theta, options_.scale)}};
  request.maxTokens = 1;
  request.temperature = 0.0;
  request.seed = options_.seed;
  request.topLogprobs = options_.topLogprobs;
  auto response = client_->complete(request);
  if (!response) return response.error();
  const std::string provenance =
      fmt::format("{}:{}{}", kBackendId, client_->config().model, response.value().fromCache ? ":cache" : "");

  if (!response.value().hasLogprobs) {
    if (options_.pointEstimateWithoutLogprobs) {
      if (auto label = tokenLabel(response.value().content)) {
        const int rating = options_.scale == RatingScale::Digits ? *label : *label - 1;
        if (rating >= 0 && rating <= 10)
          return Assessment::fromRatings(RatingDistribution::pointMass(rating), provenance + ":point-estimate");
      }
    }
    return Error{ErrorKind::NoLogprobs,
                 fmt::format("the server returned no top_logprobs for model {}; use a server that supports "
                             "log-probabilities or the offline descriptor model",
                             client_->config().model),
                 server};
  }

  LabelMass labels = readLabels(response.value().firstTokenTop);
  bool cached = response.value().fromCache;
  if (needsSplitFollowUp(labels, options_.scale, options_.split, options_.splitThreshold)) {
    ChatRequest followUp = request;
    followUp.messages.push_back({"assistant", "1"});
    followUp.extraBody = options_.followUpExtraBody;
    auto second = client_->complete(followUp);
    if (!second) return second.error();
    if (!second.value().hasLogprobs)
      return Error{ErrorKind::NoLogprobs, "the split-numeral follow-up returned no top_logprobs", server};
    labels = applySplitFollowUp(labels, options_.scale, second.value().firstTokenTop);
    cached = cached && second.value().fromCache;
  }
  auto ratings = toRatings(labels, options_.scale, options_.renormalize, options_.minCoverage, server);
  if (!ratings) return ratings.error();
  return Assessment::fromRatings(ratings.value(),
                                 fmt::format("{}:{}{}", kBackendId, client_->config().model, cached ? ":cache" : ""));
}

Status LlmPreferenceModel::learn(std::span<const FeedbackRecord> records) {
  history_.insert(history_.end(), records.begin(), records.end());
  Status status = rewriteTheta();
  if (!status && faults_) faults_->recordLearningFailure(status.error());
  return status;
}

Status LlmPreferenceModel::rewriteTheta() {
  if (!client_) return Error{ErrorKind::Configuration, "the language-model backend has no chat client"};
  ChatRequest request;
  request.messages = {{"user", renderLearningPrompt(options_.prompts, theta_, history_)}};
  request.maxTokens = options_.learningMaxTokens;
  request.temperature = options_.learningTemperature;
  request.seed = options_.seed;
  request.topLogprobs = 0;
  auto response = client_->complete(request);
  if (!response) return response.error();
  std::string text = trimmed(response.value().content);
  if (text.empty())
    return Error{ErrorKind::MalformedResponse, "the learning reply is empty; theta is unchanged", client_->server()};
  // The reply becomes the stored summary (profile.json, models/*.json): a server that echoes the credential it was
  // sent must not put it there, so the summary is redacted as every quoted server message is (Redaction.h).
  theta_ = redactSecrets(text, secretFromEnvironment(client_->config().apiKeyEnv));
  return {};
}

nlohmann::json LlmPreferenceModel::saveState() const {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& r : history_) history.push_back(toJson(r));
  return nlohmann::json{{"backend", kBackendId},
                        {"format", kStateFormat},
                        {"model", client_ ? client_->config().model : std::string()},
                        {"theta", theta_},
                        {"history", std::move(history)}};
}

Status LlmPreferenceModel::loadState(const nlohmann::json& state) {
  auto bad = [](const std::string& what) { return Error{ErrorKind::InvalidState, what}; };
  if (!state.is_object()) return bad("the state is not a JSON object");
  if (!state.contains("backend") || state["backend"] != kBackendId)
    return bad(fmt::format("the state was not saved by the {} backend", kBackendId));
  if (!state.contains("format") || state["format"] != kStateFormat)
    return bad(fmt::format("unsupported state format (expected {})", kStateFormat));
  if (!state.contains("theta") || !state["theta"].is_string()) return bad("the state has no string \"theta\"");
  if (!state.contains("history") || !state["history"].is_array()) return bad("the state has no \"history\" list");
  std::vector<FeedbackRecord> history;
  for (const auto& entry : state["history"]) {
    auto record = feedbackFromJson(entry);
    if (!record) return record.error();
    history.push_back(std::move(record).value());
  }
  // A summary stored before summaries were redacted may hold a credential: it is scrubbed as it is read.
  theta_ = redactSecrets(state["theta"].get<std::string>(),
                         client_ ? secretFromEnvironment(client_->config().apiKeyEnv) : std::string());
  history_ = std::move(history);
  return {};
}

}  // namespace cbtl::textpref
