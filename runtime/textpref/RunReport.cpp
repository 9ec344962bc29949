#include "runtime/textpref/RunReport.h"

#include "runtime/textpref/TextBackend.h"

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

}  // namespace cbtl::textpref
