// RunReport.h — what one run (a `cbtl run` trial, each trial of `cbtl experiment`) records about its text
// backend: which backend, server and model it used, and how often the language model failed.
//
// Every function accepts a null backend, which the runtime reads as the offline default (no server, no faults).
// A run calls beginRunFaults() when it starts (so a backend shared by several trials reports each trial's own
// failures; an open circuit breaker stays open), runFaults() when it ends, and writeLlmReport() to store both in
// its output folder as llm.json:
//   {"text_backend": textBackendJson(backend), "faults": FaultReport::toJson()}
// llm.json is written on every way a run with an output folder ends: its normal end (writeLlmReport), an
// exception leaving the run (LlmReportGuard's destructor), and SIGINT/SIGTERM (the interrupt handler of cbtl
// calls writeLiveLlmReports(), tools/cbtl/Interrupt.h). Only SIGKILL or a power cut leave a run without one.
#pragma once

#include "runtime/textpref/FaultStats.h"
#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <list>

namespace cbtl::textpref {

class TextBackend;

inline constexpr const char* kLlmReportFile = "llm.json";

// TextBackend::identityJson(), or {"backend": "offline", "base_url": null, "model": null} for null.
nlohmann::json textBackendJson(const TextBackend* backend);

void beginRunFaults(const TextBackend* backend);
FaultReport runFaults(const TextBackend* backend);

// Writes `dir`/llm.json atomically.
Status writeLlmReport(const std::filesystem::path& dir, const TextBackend* backend, const FaultReport& faults);

// A run in progress, registered for writeLiveLlmReports() from construction to destruction. If it is destroyed
// before finish() (an exception is leaving the run: a solver or simulator failure, a failed write), the
// destructor writes `dir`/llm.json with the faults so far, best effort: a failure to write is ignored there, the
// run's own error is the one reported. `backend` (null: offline) must outlive the guard. Thread-safe.
class LlmReportGuard {
 public:
  LlmReportGuard(std::filesystem::path dir, const TextBackend* backend);
  ~LlmReportGuard();
  LlmReportGuard(const LlmReportGuard&) = delete;
  LlmReportGuard& operator=(const LlmReportGuard&) = delete;

  // The run wrote its own llm.json at its normal end: nothing more to write.
  void finish() { finished_ = true; }

  struct Entry {  // one registered run
    std::filesystem::path dir;
    const TextBackend* backend;
  };

 private:
  std::list<Entry>::iterator entry_;
  bool finished_ = false;
};

// Writes llm.json (the faults so far) for every run in progress; the number of files written. Called once by
// cbtl's interrupt handler (outside the signal handler itself) before the process exits.
int writeLiveLlmReports();

}  // namespace cbtl::textpref
