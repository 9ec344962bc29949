// UserModel.h — everything the robot has learned about one user: for every generator, its factors per
// model key ("seasoning|salt"). Keys never seen read the prior. Saved and loaded as the user profile.
//
// Profile file (JSON, documented in docs/runtime.md):
//   {"format": "cbtl-profile", "version": 1, "domain": "example",
//    "generators": {"likesRange":     {"key|member": {"temp": {"kind": "interval", "lo": 25, "hi": 35,
//                                                                  "data": [[30, true], [34, false]]}, ...}},
//                   "likesItem":      {"": {"text": {"kind": "text", "backend": "offline-descriptor-bayes-v1",
//                                                    "theta": "...what was learned, as text...",
//                                                    "state": {...the text model's saveState()...}}}}}}
// Only the data is stored; the fitted state is recomputed on load, so a profile can never disagree with
// itself (a text model's state is its feedback history, plus theta for a language model; "theta" beside it is
// for people reading the profile and is not read back). Loading validates
// everything against the program and reports the first problem with its JSON path: every generator, factor label
// and factor kind must be the program's, a model key must have the shape of the generator's `per` parts, and a
// text factor's state must come from the backend this run uses. Loading is linear in the number of data points.
//
// Copying a UserModel deep-copies every factor, text models included (TextFactor.h): the copy learns alone.
#pragma once

#include "runtime/model/Factor.h"

#include "ir/ConstraintGraph.h"

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::model {

struct ProfileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class GeneratorState {
 public:
  // `textBackend` makes the models of text factors (null: the offline default).
  explicit GeneratorState(const ir::Generator& spec,
                          const std::shared_ptr<const textpref::TextBackend>& textBackend = nullptr);
  const ir::Generator& spec() const { return *spec_; }
  // The factors for a key; the prior when the key has no data. The reference stays valid until reset().
  const std::vector<Factor>& factors(const std::string& key) const;
  std::vector<Factor>& mutableFactors(const std::string& key);
  const std::map<std::string, std::vector<Factor>>& keys() const { return byKey_; }
  void reset() { byKey_.clear(); }
  // Bumped on every change, so evaluators can cache per-key look-ups.
  std::uint64_t version() const { return version_; }
  void touch() { ++version_; }

 private:
  const ir::Generator* spec_;
  std::vector<Factor> prior_;
  std::map<std::string, std::vector<Factor>> byKey_;
  std::uint64_t version_ = 0;
};

class UserModel {
 public:
  // Text factors get their models from `textBackend`; null means the offline descriptor model
  // (defaultTextBackend()), which needs no network and no key.
  explicit UserModel(const ir::ConstraintGraph& graph,
                     std::shared_ptr<const textpref::TextBackend> textBackend = nullptr);

  std::size_t size() const { return generators_.size(); }
  GeneratorState& generator(std::size_t i) { return generators_[i]; }
  const GeneratorState& generator(std::size_t i) const { return generators_[i]; }
  void reset();
  // Total number of labelled examples held (a text factor counts its feedback records).
  std::size_t dataCount() const;

  std::string toJson() const;
  // Throws ProfileError naming `source` and the JSON path of the first problem.
  void fromJson(const std::string& text, const std::string& source);
  void save(const std::string& path) const;  // atomic: written to a temporary file, then renamed
  void load(const std::string& path);

 private:
  std::string domain_;
  const ir::ConstraintGraph*
      graph_;  // the program the profile must fit (outlives the model, like the generators' specs)
  std::vector<GeneratorState> generators_;
};

}  // namespace cbtl::model
