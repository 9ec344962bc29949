// LoadedProgram.h — the one place that joins the wings: a .cbtl file compiled by the front end, its world
// scene bound to the language's robot built-ins, and the graph prepared for execution by the runtime.
//
// Loading never throws for bad input: the compiler's diagnostics (rendered, with locations), a missing or bad
// scene, or the runtime's RuntimeError end up in `errors()` and leave `ok()` false.
#pragma once

#include "compiler/driver/TranslationUnit.h"
#include "runtime/approach/PreparedProgram.h"
#include "runtime/core/Builtins.h"

#include <memory>
#include <string>

namespace cbtl::world {
class Scene;
}

namespace cbtl::app {

class LoadedProgram : public approach::PreparedProgram {
 public:
  static std::unique_ptr<LoadedProgram> load(const std::string& path, const std::string& stdlibDir = "",
                                             rt::Builtins builtins = rt::Builtins::standard());

  // The same for text already in memory (tests, the REPL); `path` names it in messages.
  static std::unique_ptr<LoadedProgram> fromSource(const std::string& path, std::string text,
                                                   const std::string& stdlibDir = "",
                                                   rt::Builtins builtins = rt::Builtins::standard());

  // Robot domains: the scene of worldPath(), loaded once and shared read-only (the world built-ins read it, and
  // the domain simulators get it through app/SimulatorFacts.h); null without a `world` line.
  const std::shared_ptr<const world::Scene>& scene() const { return scene_; }

 private:
  explicit LoadedProgram(std::string path) : PreparedProgram(std::move(path)) {}
  void prepareCompiled(bool compiled, const std::string& lastPass, rt::Builtins builtins);
  // Shared with the base's graph pointer, so the graph outlives everything prepared from it.
  std::shared_ptr<TranslationUnit> tu_;
  std::shared_ptr<const world::Scene> scene_;
};

}  // namespace cbtl::app
