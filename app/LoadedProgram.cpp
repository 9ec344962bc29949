#include "app/LoadedProgram.h"

#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/driver/Pipeline.h"
#include "robot/bind/WorldBuiltins.h"
#include "robot/world/Scene.h"
#include "runtime/sim/DomainSimulator.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

namespace cbtl::app {

namespace {

CompileOptions compileOptions(const std::string& stdlibDir) {
  CompileOptions options;
  options.stdlibDir = stdlibDir;
  return options;
}

// The simulator's robot state becomes the reference state of the program's world built-ins.
bool syncRobotWorld(const rt::Program& program, const sim::DomainSimulator& simulator) {
  const world::WorldState* state = simulator.worldState();
  if (state == nullptr || program.host() == nullptr) return true;
  return bind::setWorldReference(program.host(), *state);
}

}  // namespace

std::unique_ptr<LoadedProgram> LoadedProgram::load(const std::string& path, const std::string& stdlibDir,
                                                   rt::Builtins builtins) {
  auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram(path));
  if (!std::ifstream(path).good()) {
    lp->setErrors(fmt::format("error: cannot read file '{}'\n", path));
    return lp;
  }
  lp->tu_ = std::make_shared<TranslationUnit>(compileOptions(stdlibDir));
  const PipelineResult r = compileFile(*lp->tu_, path);
  lp->prepareCompiled(r.outcome == PipelineOutcome::Ok, r.lastPass, std::move(builtins));
  return lp;
}

std::unique_ptr<LoadedProgram> LoadedProgram::fromSource(const std::string& path, std::string text,
                                                         const std::string& stdlibDir, rt::Builtins builtins) {
  auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram(path));
  lp->tu_ = std::make_shared<TranslationUnit>(compileOptions(stdlibDir));
  const PipelineResult r = compileSource(*lp->tu_, path, std::move(text));
  lp->prepareCompiled(r.outcome == PipelineOutcome::Ok, r.lastPass, std::move(builtins));
  return lp;
}

void LoadedProgram::prepareCompiled(bool compiled, const std::string& lastPass, rt::Builtins builtins) {
  if (!compiled) {
    std::string errors;
    for (const auto& d : tu_->diags.sorted()) errors += renderDiagnosticText(d, tu_->sources);
    if (errors.empty()) errors = fmt::format("{}: the compiler failed in pass '{}'\n", path(), lastPass);
    setErrors(std::move(errors));
    return;
  }
  const ir::ConstraintGraph& graph = tu_->graph;
  WorldSync sync;
  if (!graph.world.empty()) {
    namespace fs = std::filesystem;
    setWorldPath((fs::path(path()).parent_path() / graph.world).lexically_normal().string());
    const world::SceneLoadResult scene = world::Scene::loadFile(worldPath());
    if (scene.status != world::LoadStatus::Ok) {
      setErrors(fmt::format("error: {}: world scene '{}': {}\n", path(), graph.world, scene.message));
      return;
    }
    scene_ = scene.scene;
    builtins = bind::withWorld(std::move(builtins), scene_);
    sync = syncRobotWorld;
  }
  // The graph lives in the translation unit: share it (and keep the unit alive) without copying.
  prepare(std::shared_ptr<const ir::ConstraintGraph>(tu_, &graph), std::move(builtins), std::move(sync));
  if (ok() || !graph.world.empty()) return;
  // A robot-world built-in in a file without a scene: say what is missing, not just what failed.
  for (const auto& name : bind::worldBuiltinNames()) {
    if (errors().find("'" + name + "' has no implementation") != std::string::npos) {
      setErrors(errors() +
                fmt::format("note: '{}' reads the robot world: declare its scene with `world \"scene.xml\";`\n", name));
      break;
    }
  }
}

}  // namespace cbtl::app
