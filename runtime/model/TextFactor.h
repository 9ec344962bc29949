// TextFactor.h — a `model text(subject, prompt: ..., learning: ..., scale: ..., rating: ...)` factor: P(the user
// would like the subject), answered by a text-preference model (runtime/textpref, docs/textpref.md).
//
// The factor owns one textpref::TextPreferenceModel, made by a textpref::TextBackend: the offline descriptor model
// by default (no network, no key), or a language model. Its parameter theta is the model's state, learned from
// (subject, liked) records.
//
// Contracts:
//  - A generator may name a context (`context: [foodOnPlate, mealSetting]`): the subject is judged in it (the
//    ConstraintPrompt shows it; the offline model has features per context value and subject), and every learned
//    record carries the context of the observation the feedback was about.
//  - Copying deep-copies what was learned: the copy gets a fresh model from the same backend and loads the
//    original's saveState(), so learning on a copy never changes the original (the evaluation agent works on a
//    copy of the training agent's user model). A language-model backend's client and response cache are shared
//    between copies; they hold no learned state. A copy throws std::runtime_error only if the fresh model rejects
//    the original's own state (a backend bug).
//  - probability() is called in the solver's inner loop. Assessments are cached per context and subject name until
//    the next learn(), loadState() or reset(); a cache hit looks two names up in hash maps and allocates nothing. A
//    failed assessment gives the generator's `fallback` (textpref::assessOrFallback) and is cached too, so an
//    unreachable server is asked once per subject and learning step, not once per candidate.
//  - `scale: relative` (the reference's rule) divides by the best probability among the available
//    subjects, so the best one has P = 1. "Available" is what the caller passes: the values the CSP can choose
//    (solver/PersonalEvaluator.h: the members of the variable's observed set, e.g. the books on the shelves, or
//    the whole item set / enum when the domain is fixed). A subject without a fixed domain (a text) is scored
//    absolutely.
//  - Like the models it owns, a TextFactor is used from one thread at a time; probability() is logically const
//    (assessing never changes what was learned) but fills the cache.
#pragma once

#include "runtime/textpref/Prompts.h"
#include "runtime/textpref/TextPreferenceModel.h"

#include "ir/ConstraintGraph.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>

namespace cbtl::textpref {
class TextBackend;
}

namespace cbtl::model {

// The offline descriptor backend with default options, shared by every user model that is not given another.
std::shared_ptr<const textpref::TextBackend> defaultTextBackend();

// The context a subject is judged in (the parts of the observation the generator's `context:` names), with the
// key that identifies it in the factor's cache. Built once per change of the context, not per candidate.
struct KeyedContext {
  textpref::Context context;
  std::string key;  // "" for the empty context

  KeyedContext() = default;
  explicit KeyedContext(textpref::Context c);
  // The shared empty context.
  static const KeyedContext& none();
};

class TextFactor {
 public:
  enum class Scale { Absolute, Relative };

  // A fresh (prior) factor for a generator's `text(...)` model. `backend` null means defaultTextBackend();
  // `fallback` is the generator's `fallback` probability.
  TextFactor(const ir::ModelFactor& spec, double fallback, std::shared_ptr<const textpref::TextBackend> backend);

  TextFactor(const TextFactor& other);
  TextFactor& operator=(const TextFactor& other);
  TextFactor(TextFactor&&) noexcept = default;
  TextFactor& operator=(TextFactor&&) noexcept = default;
  ~TextFactor();

  // P(holds) for `subject` in `context`. `available`: the subjects the CSP can choose, for relative scaling (empty:
  // absolute); the best of them is taken in the same context.
  double probability(const textpref::Item& subject, std::span<const textpref::Item> available,
                     const KeyedContext& context = KeyedContext::none()) const;
  // The model's own assessment of `subject` in `context` (absolute, with its rating bins and provenance), the
  // fallback on error.
  textpref::Assessment assess(const textpref::Item& subject,
                              const textpref::Context& context = textpref::Context{}) const;

  // Learns that the user liked (or did not like) `subject` in `context`: one FeedbackRecord {subject, context, no
  // text, liked}. On failure (a language model could not rewrite theta) the record stays in the history, theta is
  // kept and the error is returned.
  textpref::Status learn(const textpref::Item& subject, bool liked,
                         const textpref::Context& context = textpref::Context{});
  // Back to the prior: a fresh model.
  void reset();

  // The profile's view: the backend's id and the model's state. loadState() leaves the factor unchanged on error.
  std::string backendId() const { return model_->backendId(); }
  nlohmann::json saveState() const { return model_->saveState(); }
  textpref::Status loadState(const nlohmann::json& state);

  const textpref::TextPreferenceModel& model() const { return *model_; }
  std::size_t historySize() const { return model_->history().size(); }
  Scale scale() const { return scale_; }
  double fallback() const { return fallback_; }
  // Assessments that failed and fell back, and the last error's description (for reports).
  std::size_t fallbackCount() const { return fallbacks_; }
  const std::string& lastError() const { return lastError_; }

 private:
  double absolute(const textpref::Item& subject, const KeyedContext& context) const;
  void forget() const;  // drops every cached assessment

  std::shared_ptr<const textpref::TextBackend> backend_;
  textpref::PromptTemplates prompts_;
  textpref::RatingScale rating_ = textpref::RatingScale::Digits;
  Scale scale_ = Scale::Absolute;
  double fallback_ = 0.5;
  std::unique_ptr<textpref::TextPreferenceModel> model_;

  // Caches, valid until the model learns (see the contracts above).
  // context key -> subject name -> absolute probability
  mutable std::unordered_map<std::string, std::unordered_map<std::string, double>> cache_;
  mutable std::size_t fallbacks_ = 0;
  mutable std::string lastError_;
};

}  // namespace cbtl::model
