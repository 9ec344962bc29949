// RunReport.h — what one run (a `cbtl run` trial, each trial of `cbtl experiment`) records about its text
// backend: which backend, server and model it used, and how often the language model failed.
//
// Every function accepts a null backend, which the runtime reads as the offline default (no server, no faults).
// A run calls beginRunFaults() when it starts (so a backend shared by several trials reports each trial's own
// failures; an open circuit breaker stays open), runFaults() when it ends, and writeLlmReport() to store both in
// its output folder as llm.json:
//   {"text_backend": textBackendJson(backend), "faults": FaultReport::toJson()}
#pragma once

#include "runtime/textpref/FaultStats.h"
#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace cbtl::textpref {

class TextBackend;

inline constexpr const char* kLlmReportFile = "llm.json";

// TextBackend::identityJson(), or {"backend": "offline", "base_url": null, "model": null} for null.
nlohmann::json textBackendJson(const TextBackend* backend);

void beginRunFaults(const TextBackend* backend);
FaultReport runFaults(const TextBackend* backend);

// Writes `dir`/llm.json atomically.
Status writeLlmReport(const std::filesystem::path& dir, const TextBackend* backend, const FaultReport& faults);

}  // namespace cbtl::textpref
