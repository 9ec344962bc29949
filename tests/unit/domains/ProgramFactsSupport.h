// ProgramFactsSupport.h — the facts a domain simulator gets from its program, for tests that create simulators
// directly: the domain's .cbtl file (under CBTL_DOMAINS_DIR, the source tree's domains/) compiled once per test
// process, so the scene is loaded once and the item sets are the program's own.
#pragma once

#include "app/LoadedProgram.h"
#include "app/SimulatorFacts.h"
#include "domains/ProgramFacts.h"

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

namespace cbtl::test {

// The facts of domains/<domain>/<domain>.cbtl. Throws std::runtime_error with the compiler's messages when the
// file does not load.
inline const domains::ProgramFacts& programFacts(const std::string& domain) {
  static std::map<std::string, domains::ProgramFacts> loaded;
  auto it = loaded.find(domain);
  if (it == loaded.end()) {
    const auto program =
        app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/" + domain + "/" + domain + ".cbtl");
    if (!program->ok()) throw std::runtime_error(program->errors());
    it = loaded.emplace(domain, app::simulatorFacts(*program)).first;
  }
  return it->second;
}

// The loaded scene of a domain's program (home.xml for books and cleaning).
inline std::shared_ptr<const world::Scene> programSceneOf(const std::string& domain) {
  return programFacts(domain).scene;
}

}  // namespace cbtl::test
