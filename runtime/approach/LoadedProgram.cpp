#include "runtime/approach/LoadedProgram.h"

#include "runtime/bind/WorldBuiltins.h"
#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/driver/Pipeline.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

namespace cbtl::approach {

std::unique_ptr<LoadedProgram> LoadedProgram::load(const std::string& path, const std::string& stdlibDir,
                                                   rt::Builtins builtins) {
  auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram());
  lp->path_ = path;
  if (!std::ifstream(path).good()) {
    lp->errors_ = fmt::format("error: cannot read file '{}'\n", path);
    return lp;
  }
  CompileOptions options;
  options.stdlibDir = stdlibDir;
  lp->tu_ = std::make_unique<TranslationUnit>(options);
  const PipelineResult r = compileFile(*lp->tu_, path);
  lp->prepare(r, std::move(builtins));
  return lp;
}

std::unique_ptr<LoadedProgram> LoadedProgram::fromSource(const std::string& path, std::string text,
                                                         const std::string& stdlibDir, rt::Builtins builtins) {
  auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram());
  lp->path_ = path;
  CompileOptions options;
  options.stdlibDir = stdlibDir;
  lp->tu_ = std::make_unique<TranslationUnit>(options);
  const PipelineResult r = compileSource(*lp->tu_, path, std::move(text));
  lp->prepare(r, std::move(builtins));
  return lp;
}

void LoadedProgram::prepare(const PipelineResult& r, rt::Builtins builtins) {
  if (r.outcome != PipelineOutcome::Ok) {
    for (const auto& d : tu_->diags.sorted()) errors_ += renderDiagnosticText(d, tu_->sources);
    if (errors_.empty()) errors_ = fmt::format("{}: the compiler failed in pass '{}'\n", path_, r.lastPass);
    return;
  }
  if (!tu_->graph.world.empty()) {
    namespace fs = std::filesystem;
    worldPath_ = (fs::path(path_).parent_path() / tu_->graph.world).lexically_normal().string();
    std::string error;
    if (!bind::addWorldFromFile(builtins, worldPath_, error)) {
      errors_ = fmt::format("error: {}: world scene '{}': {}\n", path_, tu_->graph.world, error);
      return;
    }
  }
  try {
    auto program = std::make_unique<rt::Program>(tu_->graph, std::move(builtins));
    for (const auto& task : tu_->graph.tasks) {
      instances_.push_back(rt::personalize(*program, task));
      actions_.emplace_back(*program, task);
    }
    learner_ = std::make_unique<Learner>(*program);
    program_ = std::move(program);
  } catch (const rt::RuntimeError& e) {
    errors_ = fmt::format("error: {}\n", e.what());
    if (tu_->graph.world.empty()) {
      // A robot-world built-in in a file without a scene: say what is missing, not just what failed.
      for (const auto& name : bind::worldBuiltinNames()) {
        if (std::string(e.what()).find("'" + name + "' has no implementation") != std::string::npos) {
          errors_ += fmt::format("note: '{}' reads the robot world: declare its scene with `world \"scene.xml\";`\n", name);
          break;
        }
      }
    }
    instances_.clear();
    actions_.clear();
  }
}

void LoadedProgram::syncWorld(const sim::DomainSimulator& simulator) const {
  const world::WorldState* state = simulator.worldState();
  if (state == nullptr || program_ == nullptr || program_->host() == nullptr) return;
  if (!bind::setWorldReference(program_->host(), *state)) {
    throw rt::RuntimeError("", fmt::format("the simulator's world state does not fit the scene '{}'", worldPath_));
  }
}

std::size_t LoadedProgram::taskFor(const sim::DomainSimulator& simulator, std::size_t configured) const {
  const std::string name = simulator.requestedTask();
  if (name.empty()) return configured;
  const int t = taskIndex(name);
  if (t < 0) throw rt::RuntimeError("", fmt::format("the simulator asks for task '{}', which '{}' does not declare", name, path_));
  return static_cast<std::size_t>(t);
}

int LoadedProgram::taskIndex(const std::string& name) const {
  const auto& tasks = tu_->graph.tasks;
  if (tasks.empty()) return -1;
  if (name.empty()) return 0;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (tasks[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace cbtl::approach
