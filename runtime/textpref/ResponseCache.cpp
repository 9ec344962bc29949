#include "runtime/textpref/ResponseCache.h"

#include "runtime/textpref/Sha256.h"
#include "runtime/textpref/TextPreferenceModel.h"

#include <fmt/core.h>

#include <fstream>
#include <sstream>

namespace cbtl::textpref {
namespace {
constexpr const char* kFormat = "cbtl-textpref-cache-1";
}

const char* cacheModeName(CacheMode mode) {
  switch (mode) {
    case CacheMode::Off:
      return "off";
    case CacheMode::ReadWrite:
      return "read-write";
    case CacheMode::ReadOnly:
      return "read-only";
    case CacheMode::Record:
      return "record";
  }
  return "off";
}

std::optional<CacheMode> parseCacheMode(std::string_view name) {
  for (CacheMode m : {CacheMode::Off, CacheMode::ReadWrite, CacheMode::ReadOnly, CacheMode::Record})
    if (name == cacheModeName(m)) return m;
  return std::nullopt;
}

ResponseCache::ResponseCache(std::filesystem::path root, CacheMode mode, WarningSink warn)
    : root_(std::move(root)), mode_(mode), warn_(std::move(warn)) {}

std::string canonicalJson(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string ResponseCache::keyOf(const nlohmann::json& request) { return sha256Hex(canonicalJson(request)); }

std::filesystem::path ResponseCache::pathOf(const std::string& key) const {
  if (root_.empty() || key.size() < 2) return {};
  return root_ / key.substr(0, 2) / (key + ".json");
}

std::optional<nlohmann::json> ResponseCache::lookup(const nlohmann::json& request) {
  if (mode_ == CacheMode::Off || mode_ == CacheMode::Record) return std::nullopt;
  const std::string key = keyOf(request);
  std::lock_guard lock(mutex_);
  if (auto it = memory_.find(key); it != memory_.end()) {
    ++stats_.memoryHits;
    return it->second;
  }
  const auto path = pathOf(key);
  std::error_code ec;
  if (path.empty() || !std::filesystem::exists(path, ec)) {
    ++stats_.misses;
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const nlohmann::json entry = nlohmann::json::parse(buffer.str(), nullptr, /*allow_exceptions=*/false);
  std::string problem;
  if (!in && !in.eof()) {
    problem = "cannot be read";
  } else if (entry.is_discarded() || !entry.is_object()) {
    problem = "is not valid JSON";
  } else if (!entry.contains("format") || entry["format"] != kFormat) {
    problem = "has an unknown format tag";
  } else if (!entry.contains("key") || entry["key"] != key || !entry.contains("request") ||
             keyOf(entry["request"]) != key) {
    problem = "does not match its key";
  } else if (!entry.contains("response") || !entry["response"].is_object()) {
    problem = "has no response object";
  }
  if (!problem.empty()) {
    ++stats_.corrupt;
    ++stats_.misses;
    if (warn_) warn_(fmt::format("warning: response cache entry {} {}; treating it as a miss", path.string(), problem));
    return std::nullopt;
  }
  ++stats_.diskHits;
  memory_[key] = entry["response"];
  return entry["response"];
}

void ResponseCache::store(const nlohmann::json& request, const nlohmann::json& response) {
  if (mode_ == CacheMode::Off || mode_ == CacheMode::ReadOnly) return;
  const std::string key = keyOf(request);
  std::lock_guard lock(mutex_);
  memory_[key] = response;
  ++stats_.stores;
  const auto path = pathOf(key);
  if (path.empty()) return;
  const nlohmann::json entry{{"format", kFormat}, {"key", key}, {"request", request}, {"response", response}};
  Status written =
      writeFileAtomically(path, entry.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  if (!written.ok() && warn_) warn_(fmt::format("warning: response cache: {}", written.error().message));
}

ResponseCache::Stats ResponseCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace cbtl::textpref
