#include "runtime/textpref/TextPreferenceModel.h"

#include "support/InputFile.h"

#include <fmt/core.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <fstream>
#include <sstream>
#include <system_error>

namespace cbtl::textpref {

Assessment Assessment::fromRatings(RatingDistribution ratings, std::string provenance) {
  Assessment a;
  a.ratings = ratings;
  a.probability = ratings.expectedProbability();
  a.entropyBits = bernoulliEntropyBits(a.probability);
  a.provenance = std::move(provenance);
  return a;
}

Assessment assessOrFallback(const Result<Assessment>& result, const FallbackPolicy& fallback) {
  if (result.ok()) return result.value();
  Assessment a;
  a.probability = std::clamp(fallback.probability, 0.0, 1.0);
  a.entropyBits = bernoulliEntropyBits(a.probability);
  a.provenance = fmt::format("fallback: {}", errorKindName(result.error().kind));
  return a;
}

std::vector<Assessment> scaleRelativeToBest(std::span<const Assessment> available) {
  std::vector<Assessment> out(available.begin(), available.end());
  double best = 0.0;
  for (const auto& a : out) best = std::max(best, a.probability);
  if (best <= 0.0) return out;
  for (auto& a : out) {
    a.probability = std::clamp(a.probability / best, 0.0, 1.0);
    a.entropyBits = bernoulliEntropyBits(a.probability);
  }
  return out;
}

Status writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) return Error{ErrorKind::Io, fmt::format("cannot create {}: {}", path.parent_path().string(), ec.message())};
  }
  std::filesystem::path temp = path;
  temp += fmt::format(".tmp.{}.{}", static_cast<long>(::getpid()), counter.fetch_add(1));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return Error{ErrorKind::Io, fmt::format("cannot open {} for writing", temp.string())};
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(temp, ec);
      return Error{ErrorKind::Io, fmt::format("cannot write {}", temp.string())};
    }
  }
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    return Error{ErrorKind::Io, fmt::format("cannot rename {} to {}: {}", temp.string(), path.string(), ec.message())};
  }
  return {};
}

Status saveStateFile(const TextPreferenceModel& model, const std::filesystem::path& path) {
  const std::string text = model.saveState().dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  return writeFileAtomically(path, text + "\n");
}

Status loadStateFile(TextPreferenceModel& model, const std::filesystem::path& path) {
  std::string text;
  try {
    text = support::readInputFile(path.string(), support::kMaxDataBytes, "model state");
  } catch (const support::InputFileError& e) {
    return Error{ErrorKind::Io, e.what()};
  }
  nlohmann::json state = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (state.is_discarded())
    return Error{ErrorKind::InvalidState, fmt::format("model state {} is not valid JSON", path.string())};
  Status status = model.loadState(state);
  if (!status.ok()) {
    Error e = status.error();
    e.message = fmt::format("model state {}: {}", path.string(), e.message);
    return e;
  }
  return {};
}

}  // namespace cbtl::textpref
