#include "runtime/model/TextFactor.h"

#include "runtime/textpref/TextBackend.h"

#include <algorithm>
#include <stdexcept>

namespace cbtl::model {

std::shared_ptr<const textpref::TextBackend> defaultTextBackend() {
  // The offline backend holds no client and no cache, so one instance serves every user model and thread.
  static const auto backend = std::make_shared<const textpref::TextBackend>(textpref::TextBackendConfig{});
  return backend;
}

KeyedContext::KeyedContext(textpref::Context c) : context(std::move(c)) {
  // Unit and record separators cannot occur in a .cbtl name; a value holding one could make two contexts share a
  // key, which no observed text of our domains does.
  for (const auto& [field, values] : context.fields) {
    key += field;
    for (const auto& v : values) key += '\x1f' + v;
    key += '\x1e';
  }
}

const KeyedContext& KeyedContext::none() {
  static const KeyedContext empty;
  return empty;
}

TextFactor::TextFactor(const ir::ModelFactor& spec, double fallback,
                       std::shared_ptr<const textpref::TextBackend> backend)
    : backend_(backend ? std::move(backend) : defaultTextBackend()),
      prompts_(textpref::generatorPrompts(spec.prompt, spec.learning)),
      rating_(spec.rating == ir::TextRating::Options ? textpref::RatingScale::NumberedOptions
                                                     : textpref::RatingScale::Digits),
      scale_(spec.scale == ir::TextScale::Relative ? Scale::Relative : Scale::Absolute),
      fallback_(fallback),
      model_(backend_->makeModel(prompts_, rating_)) {}

TextFactor::~TextFactor() = default;

TextFactor::TextFactor(const TextFactor& other)
    : backend_(other.backend_),
      prompts_(other.prompts_),
      rating_(other.rating_),
      scale_(other.scale_),
      fallback_(other.fallback_),
      model_(backend_->makeModel(prompts_, rating_)),
      cache_(other.cache_),
      fallbacks_(other.fallbacks_),
      lastError_(other.lastError_) {
  // The fresh model of the same backend takes the original's state; the cached assessments stay valid because
  // loadState(saveState()) restores an equal model (TextPreferenceModel.h).
  if (const textpref::Status s = model_->loadState(other.model_->saveState()); !s.ok()) {
    throw std::runtime_error("cannot copy a text model: " + s.error().describe());
  }
}

TextFactor& TextFactor::operator=(const TextFactor& other) {
  if (this != &other) *this = TextFactor(other);
  return *this;
}

void TextFactor::forget() const { cache_.clear(); }

textpref::Assessment TextFactor::assess(const textpref::Item& subject, const textpref::Context& context) const {
  const auto result = model_->assess(subject, context);
  if (!result.ok()) {
    ++fallbacks_;
    lastError_ = result.error().describe();
  }
  return textpref::assessOrFallback(result, textpref::FallbackPolicy{fallback_});
}

double TextFactor::absolute(const textpref::Item& subject, const KeyedContext& context) const {
  auto& bySubject = cache_[context.key];  // allocates only the first time a context is seen
  if (auto it = bySubject.find(subject.name); it != bySubject.end()) return it->second;
  const double p = assess(subject, context.context).probability;
  bySubject.emplace(subject.name, p);
  return p;
}

double TextFactor::probability(const textpref::Item& subject, std::span<const textpref::Item> available,
                               const KeyedContext& context) const {
  const double p = absolute(subject, context);
  if (scale_ != Scale::Relative || available.empty()) return p;
  // The same rule as textpref::scaleRelativeToBest, over probabilities that are cached anyway. Recomputed on
  // every call: the available values differ from CSP to CSP (a few cached look-ups).
  double best = 0.0;
  for (const auto& item : available) best = std::max(best, absolute(item, context));
  if (best <= 0.0) return p;
  return std::clamp(p / best, 0.0, 1.0);
}

textpref::Status TextFactor::learn(const textpref::Item& subject, bool liked, const textpref::Context& context) {
  const textpref::FeedbackRecord record{subject, context, std::string(), liked};
  const textpref::Status status = model_->learn(std::span<const textpref::FeedbackRecord>(&record, 1));
  forget();  // the history changed even when theta could not be rewritten
  return status;
}

void TextFactor::reset() {
  model_ = backend_->makeModel(prompts_, rating_);
  forget();
  fallbacks_ = 0;
  lastError_.clear();
}

textpref::Status TextFactor::loadState(const nlohmann::json& state) {
  textpref::Status status = model_->loadState(state);
  if (status.ok()) forget();
  return status;
}

}  // namespace cbtl::model
