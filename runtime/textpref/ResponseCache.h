// ResponseCache.h — chat-completion responses cached on disk, with an in-memory layer in front.
//
// Key: the SHA-256 (hex) of the canonical request JSON, i.e. nlohmann::json::dump() of the request body, whose
// object keys are sorted, without whitespace. The API key is never part of the request body, so it never
// reaches the key or the files. Layout: <root>/<first two hex digits>/<key>.json, one file per entry:
//   {"format": "cbtl-textpref-cache-1", "key": "<key>", "request": {...}, "response": {...}}
// Files are written atomically (temporary file + rename). Only successful responses are stored; errors never.
// A file that is not JSON, has another format tag, or whose request does not hash to its key is corrupt: it is
// reported through the warning sink and treated as a miss (read-write mode overwrites it on the next store).
//
// Modes: Off (no lookups, no stores), ReadWrite (default), ReadOnly (lookups only; the client turns a miss into
// a CacheMiss error instead of reaching the network: the mode for tests and CI), Record (always ask the
// server, then overwrite the entry). Thread-safe.
#pragma once

#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

namespace cbtl::textpref {

enum class CacheMode { Off, ReadWrite, ReadOnly, Record };

// The canonical text of a JSON value: sorted object keys, no whitespace, invalid UTF-8 replaced by U+FFFD (so
// that it never throws). Request bodies are sent and hashed in this form.
std::string canonicalJson(const nlohmann::json& value);

const char* cacheModeName(CacheMode mode);
// Parses "off", "read-write", "read-only", "record".
std::optional<CacheMode> parseCacheMode(std::string_view name);

// Receives one human-readable line per warning (corrupt entry, failed write). Default: none.
using WarningSink = std::function<void(const std::string&)>;

class ResponseCache {
 public:
  // `root` may be empty: then only the in-memory layer is used.
  ResponseCache(std::filesystem::path root, CacheMode mode, WarningSink warn = {});

  CacheMode mode() const { return mode_; }
  const std::filesystem::path& root() const { return root_; }

  // Key of a request body: sha256Hex(canonicalJson(request)).
  static std::string keyOf(const nlohmann::json& request);
  // Where the entry of `key` lives on disk (empty path when the cache has no root).
  std::filesystem::path pathOf(const std::string& key) const;

  // The cached response for `request`, or nullopt on a miss (always nullopt in Off and Record modes).
  std::optional<nlohmann::json> lookup(const nlohmann::json& request);
  // Stores a successful response (no-op in Off and ReadOnly modes). A failed disk write is a warning: the entry
  // still lives in memory, and the caller's answer is unaffected.
  void store(const nlohmann::json& request, const nlohmann::json& response);

  struct Stats {
    int memoryHits = 0;
    int diskHits = 0;
    int misses = 0;
    int corrupt = 0;
    int stores = 0;
  };
  Stats stats() const;

 private:
  std::filesystem::path root_;
  CacheMode mode_;
  WarningSink warn_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, nlohmann::json> memory_;
  Stats stats_;
};

}  // namespace cbtl::textpref
