#include "runtime/textpref/RunReport.h"

#include "runtime/textpref/TextBackend.h"

#include <mutex>

namespace cbtl::textpref {

nlohmann::json textBackendJson(const TextBackend* backend) {
  if (backend != nullptr) return backend->identityJson();
  return nlohmann::json{{"backend", "offline"}, {"base_url", nullptr}, {"model", nullptr}};
}

void beginRunFaults(const TextBackend* backend) {
  if (backend != nullptr) backend->resetFaultCounts();
}

FaultReport runFaults(const TextBackend* backend) {
  return backend != nullptr ? backend->faultReport() : FaultReport{};
}

Status writeLlmReport(const std::filesystem::path& dir, const TextBackend* backend, const FaultReport& faults) {
  const nlohmann::json report{{"text_backend", textBackendJson(backend)}, {"faults", faults.toJson()}};
  return writeFileAtomically(dir / kLlmReportFile,
                             report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

namespace {
// The runs in progress. A list, so that each guard's iterator stays valid while others come and go. Never
// destroyed: the interrupt's exit thread may still be writing while the main thread returns from main().
std::mutex& liveMutex() {
  static auto* m = new std::mutex;  // NOLINT(cppcoreguidelines-owning-memory)
  return *m;
}
std::list<LlmReportGuard::Entry>& liveRuns() {
  static auto* runs = new std::list<LlmReportGuard::Entry>;  // NOLINT(cppcoreguidelines-owning-memory)
  return *runs;
}
}  // namespace

LlmReportGuard::LlmReportGuard(std::filesystem::path dir, const TextBackend* backend) {
  std::lock_guard lock(liveMutex());
  entry_ = liveRuns().insert(liveRuns().end(), Entry{std::move(dir), backend});
}

LlmReportGuard::~LlmReportGuard() {
  std::lock_guard lock(liveMutex());
  try {
    if (!finished_) (void)writeLlmReport(entry_->dir, entry_->backend, runFaults(entry_->backend));
  } catch (...) {  // NOLINT(bugprone-empty-catch): best effort while another error leaves the run
  }
  liveRuns().erase(entry_);
}

int writeLiveLlmReports() {
  std::lock_guard lock(liveMutex());
  int written = 0;
  for (const auto& run : liveRuns())
    if (writeLlmReport(run.dir, run.backend, runFaults(run.backend)).ok()) ++written;
  return written;
}

}  // namespace cbtl::textpref
