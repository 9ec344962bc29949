// OfflineDescriptorModel.h — the offline descriptor model: Bayesian logistic regression over item descriptors.
//
// This is the embedded default text-preference backend: no network, no key, deterministic. It is NOT a language
// model and knows nothing beyond the descriptors declared for the items: two items share evidence only through
// descriptor values they have in common.
//
// Features of (item, context), all binary: a bias; the item's identity ("item=<name>"); one per descriptor value
// ("<field>=<value>", lower-cased; fields in `ignoredFields`, e.g. title, are skipped); and, when the context is not
// empty and `contextPairs` is set, one per (context value, item name) and (context value, descriptor value) pair,
// so that "bbq with fries" can differ from "bbq with carrots". Prior: independent zero-mean Gaussians on the weights,
// with a variance per feature family. Posterior: the MAP weights by Newton's method and the Laplace covariance
// (inverse Hessian). Prediction: the logit a = w·x is Gaussian under the Laplace posterior (features never seen
// carry their prior variance); the mean m and variance v of sigmoid(a) are computed by quadrature; the 11 bins are
// the Beta-Binomial(10, α, β) with the Beta moment-matched to (m, v), so P(holds) = α/(α+β) = m exactly and the
// bins are wide when the model is unsure. Feedback: `liked` when present, otherwise classifyFeedbackText(text);
// records without either are kept in the history but carry no label.
#pragma once

#include "runtime/textpref/TextPreferenceModel.h"

#include <map>
#include <string>
#include <vector>

namespace cbtl::textpref {

struct OfflineModelOptions {
  double biasPriorVariance = 0.25;       // small: one liked item barely moves unrelated items
  double identityPriorVariance = 2.0;    // direct feedback on an item counts most for that item
  double descriptorPriorVariance = 2.0;  // shared descriptors carry evidence between items
  double contextPairPriorVariance = 1.0;
  bool contextPairs = true;
  std::vector<std::string> ignoredFields = {"title", "description", "summary"};
  int newtonIterations = 100;
  double newtonTolerance = 1e-10;
  double minConcentration = 0.5;  // bounds on α+β of the moment-matched Beta
  double maxConcentration = 1e4;
};

class OfflineDescriptorModel final : public TextPreferenceModel {
 public:
  static constexpr const char* kBackendId = "offline-descriptor-bayes-v1";

  explicit OfflineDescriptorModel(OfflineModelOptions options = {});

  std::string backendId() const override { return kBackendId; }
  Result<Assessment> assess(const Item& item, const Context& context) override;
  Status learn(std::span<const FeedbackRecord> records) override;
  std::string thetaText() const override;
  const std::vector<FeedbackRecord>& history() const override { return history_; }
  nlohmann::json saveState() const override;
  Status loadState(const nlohmann::json& state) override;

  // Feature names of (item, context), sorted; exposed for explanations and tests.
  std::vector<std::string> features(const Item& item, const Context& context) const;
  // Posterior mean and standard deviation of one feature's weight (prior values for an unseen feature).
  double weightMean(const std::string& feature) const;
  double weightStdDev(const std::string& feature) const;
  // Records that carried a label (liked, or text the lexicon could read).
  int labelledCount() const { return labelled_; }

  const OfflineModelOptions& options() const { return options_; }

 private:
  double priorVariance(const std::string& feature) const;
  Status refit();

  OfflineModelOptions options_;
  std::vector<FeedbackRecord> history_;
  std::map<std::string, int> index_;  // feature -> row/column
  std::vector<double> mean_;          // MAP weights
  std::vector<double> covariance_;    // dense, row-major, index_.size()^2
  int labelled_ = 0;
};

}  // namespace cbtl::textpref
