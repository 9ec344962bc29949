// LoadedProgram.h — the one place that joins the wings: a .cbtl file compiled by the front end (or a graph
// that `cbtlc emit --format json` wrote, read back without the front end), its world scene bound to the
// language's robot built-ins, and the graph prepared for execution by the runtime.
//
// Which of the two a file is, its content says, not its name: text whose first character (after white space)
// is '{' is an emitted graph (ir::looksLikeGraphJson; no .cbtl program can start so), anything else is .cbtl
// source. An emitted graph's `world` scene is looked for as app/ScenePath.h describes; the standard library
// was compiled into the graph, so `stdlibDir` does not apply to it.
//
// Loading never throws for bad input: the compiler's diagnostics (rendered, with locations), the JSON reader's
// error (with the JSON Pointer of the offending field) or the validator's problems, a missing or bad scene,
// or the runtime's RuntimeError end up in `errors()` and leave `ok()` false.
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
  void prepareEmitted(const std::string& text, rt::Builtins builtins);
  // Binds the scene (when the graph has a world) and prepares the graph for execution.
  void prepareGraph(std::shared_ptr<const ir::ConstraintGraph> graph, const std::string& scene, rt::Builtins builtins);
  // Shared with the base's graph pointer, so the graph outlives everything prepared from it; null for an
  // emitted graph, which the base owns alone.
  std::shared_ptr<TranslationUnit> tu_;
  std::shared_ptr<const world::Scene> scene_;
};

}  // namespace cbtl::app
