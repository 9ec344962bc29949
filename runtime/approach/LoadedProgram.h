// LoadedProgram.h — a .cbtl file compiled and prepared for execution, with everything it owns: the
// translation unit (sources, diagnostics, graph), the executable Program, each task's personalized
// constraint instances and actions, and the learner.
//
// Loading never throws for bad input: it reports the compiler's diagnostics (rendered, with locations) or
// the runtime's RuntimeError in `errors` and leaves `ok()` false.
#pragma once

#include "runtime/approach/ActionPlan.h"
#include "runtime/core/Builtins.h"
#include "runtime/approach/Learner.h"
#include "runtime/core/Personalization.h"
#include "runtime/core/Program.h"

#include "compiler/driver/Pipeline.h"
#include "compiler/driver/TranslationUnit.h"

#include <memory>
#include <string>
#include <vector>

namespace cbtl::approach {

class LoadedProgram {
 public:
  static std::unique_ptr<LoadedProgram> load(const std::string& path, const std::string& stdlibDir = "",
                                             rt::Builtins builtins = rt::Builtins::standard());

  // The same for text already in memory (tests, the REPL); `path` names it in messages.
  static std::unique_ptr<LoadedProgram> fromSource(const std::string& path, std::string text,
                                                   const std::string& stdlibDir = "",
                                                   rt::Builtins builtins = rt::Builtins::standard());

  bool ok() const { return program_ != nullptr; }
  const std::string& errors() const { return errors_; }  // rendered diagnostics / runtime errors
  const std::string& path() const { return path_; }

  rt::Program& program() { return *program_; }
  const rt::Program& program() const { return *program_; }
  const ir::ConstraintGraph& graph() const { return tu_->graph; }
  // Index of a task by name; the first task when `name` is empty. -1 when there is none.
  int taskIndex(const std::string& name) const;
  const std::vector<rt::PersonalInstance>& instances(std::size_t task) const { return instances_.at(task); }
  const TaskActions& actions(std::size_t task) const { return actions_.at(task); }
  const Learner& learner() const { return *learner_; }

  // Robot domains (`world "scene.xml"`): the scene file as resolved (relative to the root .cbtl file), empty
  // otherwise. The scene is loaded with the program; a missing or bad scene is a load error.
  const std::string& worldPath() const { return worldPath_; }
  // Makes the simulator's world state the one the world built-ins read (WorldHost.h). Does nothing for a
  // program without a world or a simulator without a robot scene; throws rt::RuntimeError when the state does
  // not fit the program's scene.
  void syncWorld(const sim::DomainSimulator& simulator) const;
  // The task the simulator asks for now (DomainSimulator::requestedTask), else `configured`. Throws
  // rt::RuntimeError when the simulator names a task the program lacks.
  std::size_t taskFor(const sim::DomainSimulator& simulator, std::size_t configured) const;

 private:
  void prepare(const PipelineResult& r, rt::Builtins builtins);
  std::string path_;
  std::string worldPath_;
  std::string errors_;
  std::unique_ptr<TranslationUnit> tu_;
  std::unique_ptr<rt::Program> program_;
  std::vector<std::vector<rt::PersonalInstance>> instances_;
  std::vector<TaskActions> actions_;
  std::unique_ptr<Learner> learner_;
};

}  // namespace cbtl::approach
