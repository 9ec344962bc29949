#include "runtime/textpref/OfflineDescriptorModel.h"

#include "runtime/textpref/FeedbackText.h"

#include <fmt/core.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>

namespace cbtl::textpref {
namespace {

constexpr int kStateFormat = 1;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

double sigmoid(double a) { return a >= 0 ? 1.0 / (1.0 + std::exp(-a)) : std::exp(a) / (1.0 + std::exp(a)); }

std::optional<bool> labelOf(const FeedbackRecord& r) {
  if (r.liked) return r.liked;
  return classifyFeedbackText(r.text);
}

// Mean and variance of sigmoid(a) for a ~ N(mu, var): midpoint rule over ±8 standard deviations.
std::pair<double, double> sigmoidMoments(double mu, double var) {
  if (var <= 1e-12) return {sigmoid(mu), 0.0};
  const double sd = std::sqrt(var);
  constexpr int kPoints = 400;
  const double lo = -8.0;
  const double step = 16.0 / kPoints;
  double w = 0, m1 = 0, m2 = 0;
  for (int i = 0; i < kPoints; ++i) {
    const double z = lo + (i + 0.5) * step;
    const double weight = std::exp(-0.5 * z * z);
    const double s = sigmoid(mu + sd * z);
    w += weight;
    m1 += weight * s;
    m2 += weight * s * s;
  }
  m1 /= w;
  m2 /= w;
  return {m1, std::max(0.0, m2 - m1 * m1)};
}

}  // namespace

OfflineDescriptorModel::OfflineDescriptorModel(OfflineModelOptions options) : options_(std::move(options)) {}

std::vector<std::string> OfflineDescriptorModel::features(const Item& item, const Context& context) const {
  std::set<std::string> out{"bias", "item=" + lower(item.name)};
  std::vector<std::string> itemValues{"item=" + lower(item.name)};
  for (const auto& [field, values] : item.descriptors) {
    if (std::find(options_.ignoredFields.begin(), options_.ignoredFields.end(), field) != options_.ignoredFields.end())
      continue;
    for (const auto& v : values) {
      std::string f = lower(field) + "=" + lower(v);
      out.insert(f);
      itemValues.push_back(std::move(f));
    }
  }
  if (options_.contextPairs)
    for (const auto& [field, values] : context.fields)
      for (const auto& v : values)
        for (const auto& iv : itemValues) out.insert("ctx:" + lower(field) + "=" + lower(v) + "&" + iv);
  return {out.begin(), out.end()};
}

double OfflineDescriptorModel::priorVariance(const std::string& feature) const {
  if (feature == "bias") return options_.biasPriorVariance;
  if (feature.rfind("ctx:", 0) == 0) return options_.contextPairPriorVariance;
  if (feature.rfind("item=", 0) == 0) return options_.identityPriorVariance;
  return options_.descriptorPriorVariance;
}

double OfflineDescriptorModel::weightMean(const std::string& feature) const {
  auto it = index_.find(feature);
  return it == index_.end() ? 0.0 : mean_[static_cast<std::size_t>(it->second)];
}

double OfflineDescriptorModel::weightStdDev(const std::string& feature) const {
  auto it = index_.find(feature);
  if (it == index_.end()) return std::sqrt(priorVariance(feature));
  const auto n = index_.size();
  const auto i = static_cast<std::size_t>(it->second);
  return std::sqrt(std::max(0.0, covariance_[i * n + i]));
}

Status OfflineDescriptorModel::refit() {
  index_.clear();
  mean_.clear();
  covariance_.clear();
  labelled_ = 0;
  std::vector<std::vector<int>> rows;
  std::vector<double> labels;
  for (const auto& record : history_) {
    const auto label = labelOf(record);
    if (!label) continue;
    std::vector<int> row;
    for (const auto& f : features(record.item, record.context)) {
      auto [it, inserted] = index_.emplace(f, static_cast<int>(index_.size()));
      row.push_back(it->second);
    }
    rows.push_back(std::move(row));
    labels.push_back(*label ? 1.0 : 0.0);
    ++labelled_;
  }
  const auto n = static_cast<Eigen::Index>(index_.size());
  Eigen::VectorXd precision(n);
  for (const auto& [f, i] : index_) precision[i] = 1.0 / priorVariance(f);

  // Newton's method on the convex negative log posterior; the prior makes the Hessian positive definite.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd hessian(n, n);
  for (int iter = 0; iter < options_.newtonIterations; ++iter) {
    Eigen::VectorXd gradient = precision.cwiseProduct(w);
    hessian = precision.asDiagonal();
    for (std::size_t k = 0; k < rows.size(); ++k) {
      double a = 0.0;
      for (int j : rows[k]) a += w[j];
      const double s = sigmoid(a);
      for (int j : rows[k]) gradient[j] += s - labels[k];
      const double curvature = s * (1.0 - s);
      for (int j : rows[k])
        for (int l : rows[k]) hessian(j, l) += curvature;
    }
    Eigen::LDLT<Eigen::MatrixXd> ldlt(hessian);
    if (ldlt.info() != Eigen::Success)
      return Error{ErrorKind::InvalidState, "the offline descriptor model's Hessian could not be factorised"};
    const Eigen::VectorXd step = ldlt.solve(gradient);
    w -= step;
    if (step.lpNorm<Eigen::Infinity>() < options_.newtonTolerance) break;
  }
  // Laplace covariance at the mode: recompute the Hessian at the final weights.
  hessian = precision.asDiagonal();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    double a = 0.0;
    for (int j : rows[k]) a += w[j];
    const double s = sigmoid(a);
    for (int j : rows[k])
      for (int l : rows[k]) hessian(j, l) += s * (1.0 - s);
  }
  const Eigen::MatrixXd cov = hessian.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  mean_.assign(w.data(), w.data() + n);
  covariance_.resize(static_cast<std::size_t>(n * n));
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) covariance_[static_cast<std::size_t>(i * n + j)] = cov(i, j);
  return {};
}

Result<Assessment> OfflineDescriptorModel::assess(const Item& item, const Context& context) {
  const auto n = index_.size();
  double mu = 0.0;
  double var = 0.0;
  std::vector<std::size_t> known;
  for (const auto& f : features(item, context)) {
    auto it = index_.find(f);
    if (it == index_.end()) {
      var += priorVariance(f);
    } else {
      known.push_back(static_cast<std::size_t>(it->second));
    }
  }
  for (std::size_t i : known) {
    mu += mean_[i];
    for (std::size_t j : known) var += covariance_[i * n + j];
  }
  auto [m, v] = sigmoidMoments(mu, std::max(0.0, var));
  m = std::clamp(m, 1e-9, 1.0 - 1e-9);
  const double cap = m * (1.0 - m);
  double concentration = v > 0.0 ? cap / v - 1.0 : options_.maxConcentration;
  concentration = std::clamp(concentration, options_.minConcentration, options_.maxConcentration);
  const auto ratings = RatingDistribution::betaBinomial(m * concentration, (1.0 - m) * concentration);
  Assessment a;
  a.ratings = ratings;
  a.probability = m;  // equals the Beta-Binomial's expectation up to rounding
  a.entropyBits = bernoulliEntropyBits(m);
  a.provenance = kBackendId;
  return a;
}

Status OfflineDescriptorModel::learn(std::span<const FeedbackRecord> records) {
  history_.insert(history_.end(), records.begin(), records.end());
  return refit();
}

std::string OfflineDescriptorModel::thetaText() const {
  std::set<std::string> liked, disliked;
  for (const auto& r : history_)
    if (auto label = labelOf(r))
      (*label ? liked : disliked)
          .insert(r.context.empty() ? r.item.name : r.item.name + " (" + describeContext(r.context) + ")");
  auto list = [](const std::set<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? std::string("none") : out;
  };
  std::vector<std::pair<double, std::string>> weights;
  for (const auto& [f, i] : index_)
    if (f != "bias" && f.rfind("item=", 0) != 0) weights.emplace_back(mean_[static_cast<std::size_t>(i)], f);
  std::sort(weights.begin(), weights.end());
  // The strongest few descriptors each way keep theta readable (ties broken by feature name).
  constexpr int kShown = 8;
  std::string likes, dislikes;
  int shown = 0;
  for (auto it = weights.rbegin(); it != weights.rend() && it->first > 0.05 && shown < kShown; ++it, ++shown)
    likes += fmt::format("{}{} ({:+.2f} ± {:.2f})", likes.empty() ? "" : ", ", it->second, it->first,
                         weightStdDev(it->second));
  shown = 0;
  for (auto it = weights.begin(); it != weights.end() && it->first < -0.05 && shown < kShown; ++it, ++shown)
    dislikes += fmt::format("{}{} ({:+.2f} ± {:.2f})", dislikes.empty() ? "" : ", ", it->second, it->first,
                            weightStdDev(it->second));
  return fmt::format(
      "Offline descriptor model ({} labelled of {} feedback records). Liked items: {}. Disliked items: {}. "
      "Descriptors that raise the rating: {}. Descriptors that lower it: {}.",
      labelled_, history_.size(), list(liked), list(disliked), likes.empty() ? "none" : likes,
      dislikes.empty() ? "none" : dislikes);
}

nlohmann::json OfflineDescriptorModel::saveState() const {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& r : history_) history.push_back(toJson(r));
  return nlohmann::json{{"backend", kBackendId},
                        {"format", kStateFormat},
                        {"options",
                         {{"biasPriorVariance", options_.biasPriorVariance},
                          {"identityPriorVariance", options_.identityPriorVariance},
                          {"descriptorPriorVariance", options_.descriptorPriorVariance},
                          {"contextPairPriorVariance", options_.contextPairPriorVariance},
                          {"contextPairs", options_.contextPairs},
                          {"ignoredFields", options_.ignoredFields}}},
                        {"history", std::move(history)}};
}

Status OfflineDescriptorModel::loadState(const nlohmann::json& state) {
  auto bad = [](const std::string& what) { return Error{ErrorKind::InvalidState, what}; };
  if (!state.is_object()) return bad("the state is not a JSON object");
  if (!state.contains("backend") || state["backend"] != kBackendId)
    return bad(fmt::format("the state was not saved by the {}", kBackendId));
  if (!state.contains("format") || state["format"] != kStateFormat)
    return bad(fmt::format("unsupported state format (expected {})", kStateFormat));
  if (!state.contains("history") || !state["history"].is_array()) return bad("the state has no \"history\" list");
  OfflineModelOptions options = options_;
  if (state.contains("options")) {
    const auto& o = state["options"];
    if (!o.is_object()) return bad("\"options\" must be an object");
    auto positive = [&](const char* key, double& out) -> bool {
      if (!o.contains(key)) return true;
      if (!o[key].is_number() || !(o[key].get<double>() > 0.0)) return false;
      out = o[key].get<double>();
      return true;
    };
    if (!positive("biasPriorVariance", options.biasPriorVariance) ||
        !positive("identityPriorVariance", options.identityPriorVariance) ||
        !positive("descriptorPriorVariance", options.descriptorPriorVariance) ||
        !positive("contextPairPriorVariance", options.contextPairPriorVariance))
      return bad("prior variances must be positive numbers");
    if (o.contains("contextPairs")) {
      if (!o["contextPairs"].is_boolean()) return bad("\"contextPairs\" must be a boolean");
      options.contextPairs = o["contextPairs"].get<bool>();
    }
    if (o.contains("ignoredFields")) {
      if (!o["ignoredFields"].is_array()) return bad("\"ignoredFields\" must be a list of strings");
      options.ignoredFields.clear();
      for (const auto& f : o["ignoredFields"]) {
        if (!f.is_string()) return bad("\"ignoredFields\" must be a list of strings");
        options.ignoredFields.push_back(f.get<std::string>());
      }
    }
  }
  std::vector<FeedbackRecord> history;
  for (const auto& entry : state["history"]) {
    auto record = feedbackFromJson(entry);
    if (!record) return record.error();
    history.push_back(std::move(record).value());
  }
  OfflineDescriptorModel candidate(options);
  candidate.history_ = std::move(history);
  if (Status s = candidate.refit(); !s.ok()) return s;
  *this = std::move(candidate);
  return {};
}

}  // namespace cbtl::textpref
