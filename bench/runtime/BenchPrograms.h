// BenchPrograms.h — the domains' programs, loaded once per benchmark process from the source tree (CBTL_DOMAINS_DIR).
// A program that does not load is a broken checkout: its diagnostics are printed and the process aborts.
#pragma once

#include "app/LoadedProgram.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

namespace cbtl::bench {

// domains/<domain>/<domain>.cbtl. Benchmarks run on one thread, so the cache needs no lock.
inline app::LoadedProgram& domainProgram(const std::string& domain) {
  static std::map<std::string, std::unique_ptr<app::LoadedProgram>> loaded;
  auto& lp = loaded[domain];
  if (!lp) {
    lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/" + domain + "/" + domain + ".cbtl");
    if (!lp->ok()) {
      std::fprintf(stderr, "%s", lp->errors().c_str());
      std::abort();
    }
  }
  return *lp;
}

}  // namespace cbtl::bench
