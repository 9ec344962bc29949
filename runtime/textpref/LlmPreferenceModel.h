// LlmPreferenceModel.h — a TextPreferenceModel backed by an OpenAI-compatible server (paper Appendix B).
//
// assess(): renders the ConstraintPrompt with the current theta, asks for one output token at temperature 0 with
// a fixed seed and top_logprobs, and turns the first token's distribution into the 11 rating bins (RatingReader.h,
// including the split-"10" follow-up). learn(): appends the records to the history and rewrites theta from the
// whole history with the LearningPrompt (temperature and seed from the options, no log-probabilities); the whole
// reply becomes theta. Every failure is an Error naming the server; the caller falls back as its generator
// declares (assessOrFallback in TextPreferenceModel.h). With a FaultStats (optional, shared with the backend's
// other models) every failed rating query and every failed learning request is also counted there, so that a
// run reports its fallbacks (FaultStats.h).
#pragma once

#include "runtime/textpref/ChatClient.h"
#include "runtime/textpref/FaultStats.h"
#include "runtime/textpref/Prompts.h"
#include "runtime/textpref/RatingReader.h"
#include "runtime/textpref/TextPreferenceModel.h"

#include <cstdint>
#include <memory>

namespace cbtl::textpref {

struct LlmModelOptions {
  PromptTemplates prompts;  // required: the constraint's two templates
  RatingScale scale = RatingScale::Digits;
  bool renormalize = true;   // the paper's formula; false reproduces the reference code
  double minCoverage = 0.5;  // below this the answer is UnusableRating
  SplitPolicy split = SplitPolicy::Auto;
  double splitThreshold = 0.01;
  // Extra body fields of the split follow-up only (see ChatRequest::extraBody), for servers that continue a
  // pre-filled assistant turn only when asked to (vLLM).
  nlohmann::json followUpExtraBody;
  int topLogprobs = 20;   // 1..20
  std::int64_t seed = 0;  // sent with every request
  double learningTemperature = 1.0;
  int learningMaxTokens = 400;
  // When the server returns no log-probabilities but its one-token reply is a rating, put all mass on it
  // (provenance "...:point-estimate"). This loses the uncertainty active learning needs, so it is off by default.
  bool pointEstimateWithoutLogprobs = false;
};

// The options that reproduce the reference code: numbered options, 11 top log-probabilities, no renormalisation.
LlmModelOptions referenceParityOptions(PromptTemplates prompts);

class LlmPreferenceModel final : public TextPreferenceModel {
 public:
  static constexpr const char* kBackendId = "openai-compatible";

  // `client` is shared (several constraints may use one server and one cache); it must not be null. `faults`
  // (may be null) counts this model's failures.
  LlmPreferenceModel(std::shared_ptr<ChatClient> client, LlmModelOptions options,
                     std::shared_ptr<FaultStats> faults = nullptr);

  std::string backendId() const override { return kBackendId; }
  Result<Assessment> assess(const Item& item, const Context& context) override;
  Status learn(std::span<const FeedbackRecord> records) override;
  std::string thetaText() const override { return theta_; }
  const std::vector<FeedbackRecord>& history() const override { return history_; }
  nlohmann::json saveState() const override;
  Status loadState(const nlohmann::json& state) override;

  // The same rating query with an explicit theta: a simulated user's hidden preference text is its theta.
  Result<Assessment> assessWithTheta(const Item& item, const Context& context, const std::string& theta);

  const LlmModelOptions& options() const { return options_; }

 private:
  Result<Assessment> rate(const Item& item, const Context& context, const std::string& theta);
  Status rewriteTheta();

  std::shared_ptr<ChatClient> client_;
  std::shared_ptr<FaultStats> faults_;
  LlmModelOptions options_;
  std::string theta_;
  std::vector<FeedbackRecord> history_;
};

}  // namespace cbtl::textpref
