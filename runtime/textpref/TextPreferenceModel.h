// TextPreferenceModel.h — the interface every text-preference backend implements.
//
// A personalized text constraint (a `.cbtl` generator with `model text(subject, ...)`) asks its model for
// P(holds) of one item in one context. The runtime's general personalized-constraint model interface adapts this
// one; the two implementations are LlmPreferenceModel (an OpenAI-compatible server) and OfflineDescriptorModel
// (a Bayesian model over item descriptors, no network). Both answer with the same 11-bin RatingDistribution.
//
// Contracts shared by all implementations:
//  - no exception escapes; failures are Result/Status values (Result.h);
//  - assess() never changes what the model has learned; learn() appends records to the model's history;
//  - saveState() captures everything learn() changed; loadState(saveState()) restores an equal model;
//  - a model is used from one thread at a time (the runtime owns one model per generator instance).
#pragma once

#include "runtime/textpref/Item.h"
#include "runtime/textpref/RatingDistribution.h"
#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace cbtl::textpref {

// What a model says about one item.
struct Assessment {
  RatingDistribution ratings;  // the 11 bins behind the probability
  double probability = 0.5;    // P(holds) in [0, 1]
  double entropyBits = 1.0;    // Bernoulli entropy of `probability`, in bits
  std::string provenance;      // backend id, plus "cache" when an LLM answer came from the cache

  // Builds an assessment whose probability is ratings.expectedProbability().
  static Assessment fromRatings(RatingDistribution ratings, std::string provenance);
};

class TextPreferenceModel {
 public:
  virtual ~TextPreferenceModel() = default;

  // Stable identifier of the backend, e.g. "openai-compatible" or "offline-descriptor-bayes-v1".
  virtual std::string backendId() const = 0;

  // P(holds) for `item` in `context`, as the expectation over the 11 ratings.
  virtual Result<Assessment> assess(const Item& item, const Context& context) = 0;

  // Learns from new feedback: the records are appended to the history and theta is recomputed from the whole
  // history. On failure the model keeps its previous theta (the records stay in the history).
  virtual Status learn(std::span<const FeedbackRecord> records) = 0;

  // Theta as natural-language text (the LLM's summary, or a rendering of the offline model's weights).
  virtual std::string thetaText() const = 0;

  // The full feedback history learned so far.
  virtual const std::vector<FeedbackRecord>& history() const = 0;

  // State as JSON, tagged with the backend id and a format version.
  virtual nlohmann::json saveState() const = 0;
  // Restores a state made by saveState() of the same backend; InvalidState on any mismatch, and then the model
  // is unchanged.
  virtual Status loadState(const nlohmann::json& state) = 0;
};

// What the caller does when a model fails: the generator declares a fallback probability (0.5 = unknown).
struct FallbackPolicy {
  double probability = 0.5;
};

// The assessment if there is one, otherwise the fallback probability with its entropy and provenance
// "fallback: <error kind>".
Assessment assessOrFallback(const Result<Assessment>& result, const FallbackPolicy& fallback);

// Relative scaling (`scale: relative`, the reference's rule): every probability is divided by the largest probability
// among `available`, so the best available item gets P = 1 and zero entropy. Entropies are recomputed. If every
// probability is 0 the input is returned unchanged.
std::vector<Assessment> scaleRelativeToBest(std::span<const Assessment> available);

// Writes model.saveState() to `path` atomically (temporary file, then rename).
Status saveStateFile(const TextPreferenceModel& model, const std::filesystem::path& path);
// Reads `path` and calls model.loadState(); a missing, unreadable or corrupt file is an error, never a crash.
Status loadStateFile(TextPreferenceModel& model, const std::filesystem::path& path);

// Writes `text` to `path` atomically: a temporary file in the same folder, then rename. Creates the folder.
Status writeFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace cbtl::textpref
