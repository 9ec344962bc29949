#include "app/LoadedProgram.h"

#include "app/ScenePath.h"
#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/driver/Pipeline.h"
#include "domains/DomainRegistry.h"
#include "ir/GraphJsonReader.h"
#include "ir/Validator.h"
#include "robot/actions/RobotActions.h"
#include "robot/bind/WorldBuiltins.h"
#include "robot/world/Scene.h"
#include "runtime/sim/DomainSimulator.h"
#include "support/InputFile.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

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
  // Read once, up to an emitted graph's limit; a source is held to the compiler's (smaller) one.
  std::string text;
  bool unread = false;
  std::string why;  // for a file that exists but is not one to read
  try {
    text = support::readInputFile(path, support::kMaxGraphBytes, "program");
    if (!ir::looksLikeGraphJson(text) && text.size() > support::kMaxSourceBytes) {
      unread = true;
      why = fmt::format("the program is larger than {}, the most cbtl reads as one source file",
                        support::describeBytes(support::kMaxSourceBytes));
    }
  } catch (const support::InputFileError& e) {
    unread = true;
    if (e.kind != support::InputFileError::Kind::CannotOpen) why = e.reason;
  }
  if (unread) {
    auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram(path));
    lp->setErrors(fmt::format("error: cannot read file '{}'{}\n", path, why.empty() ? "" : ": " + why));
    return lp;
  }
  return fromSource(path, std::move(text), stdlibDir, std::move(builtins));
}

std::unique_ptr<LoadedProgram> LoadedProgram::fromSource(const std::string& path, std::string text,
                                                         const std::string& stdlibDir, rt::Builtins builtins) {
  auto lp = std::unique_ptr<LoadedProgram>(new LoadedProgram(path));
  if (ir::looksLikeGraphJson(text)) {
    lp->prepareEmitted(text, std::move(builtins));
    return lp;
  }
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
  // The graph lives in the translation unit: share it (and keep the unit alive) without copying.
  prepareGraph(std::shared_ptr<const ir::ConstraintGraph>(tu_, &graph),
               graph.world.empty() ? "" : sceneOfSource(path(), graph.world), std::move(builtins));
}

void LoadedProgram::prepareEmitted(const std::string& text, rt::Builtins builtins) {
  ir::GraphReadResult read = ir::readGraphJson(text);
  if (!read.ok()) {
    setErrors(fmt::format("error: {}\n", read.describe(path())));
    return;
  }
  // The reader checked the layout; the validator checks what the compiler guarantees about the content.
  const std::vector<std::string> problems = ir::validate(read.graph);
  if (!problems.empty()) {
    std::string errors;
    for (const auto& p : problems) errors += fmt::format("error: {}: not a valid constraint graph: {}\n", path(), p);
    setErrors(std::move(errors));
    return;
  }
  auto graph = std::make_shared<const ir::ConstraintGraph>(std::move(read.graph));
  std::string scene;
  if (!graph->world.empty()) {
    const SceneLookup lookup = sceneOfEmittedGraph(path(), *graph);
    if (lookup.path.empty()) {
      std::string tried;
      for (const auto& candidate : lookup.tried) tried += (tried.empty() ? "" : ", ") + candidate;
      setErrors(fmt::format("error: {}: world scene '{}' not found (looked for {})\n", path(), graph->world, tried));
      return;
    }
    scene = lookup.path;
  }
  prepareGraph(std::move(graph), scene, std::move(builtins));
}

void LoadedProgram::prepareGraph(std::shared_ptr<const ir::ConstraintGraph> graph, const std::string& scene,
                                 rt::Builtins builtins) {
  WorldSync sync;
  if (!graph->world.empty()) {
    setWorldPath(scene);
    // The program's clearances are part of the scene: every check of every thread requires them.
    std::vector<world::BodyClearance> clearances;
    for (const ir::Clearance& c : graph->clearances)
      clearances.push_back({c.name, c.bodies, c.distance, rt::Program::where(c.span)});
    const world::SceneLoadResult loaded = world::Scene::loadFile(worldPath(), clearances);
    if (loaded.status != world::LoadStatus::Ok) {
      setErrors(fmt::format("error: {}: world scene '{}': {}\n", path(), graph->world, loaded.message));
      return;
    }
    scene_ = loaded.scene;
    builtins = bind::withWorld(std::move(builtins), scene_);
    sync = syncRobotWorld;
  }
  const bool hasWorld = !graph->world.empty();
  const std::string domain = graph->domain;
  prepare(std::move(graph), std::move(builtins), std::move(sync));
  if (ok() && hasWorld) {
    // Plans are dry-run with the executor the domain's simulator acts with.
    bind::setWorldExecutor(program().host(),
                           std::make_shared<actions::RobotActions>(domains::domainActions(domain, *scene_)));
  }
  if (ok() || hasWorld) return;
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
