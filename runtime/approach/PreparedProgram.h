// PreparedProgram.h — a constraint graph prepared for execution: the executable Program, each task's
// personalized constraint instances and actions, and the learner. Built from ir/ data only; where the graph
// came from (the compiler, an emitted JSON file) is the caller's business (app/LoadedProgram.h).
//
// Preparing never throws for bad input: the runtime's RuntimeError is reported in `errors()` and `ok()` stays
// false.
//
// Robot domains: the program's world built-ins read a reference world state that the caller's WorldSync
// updates from a simulator before each CSP (the runtime itself knows nothing of robots).
#pragma once

#include "ir/ConstraintGraph.h"
#include "runtime/approach/ActionPlan.h"
#include "runtime/approach/Learner.h"
#include "runtime/core/Builtins.h"
#include "runtime/core/Personalization.h"
#include "runtime/core/Program.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::sim {
class DomainSimulator;
}

namespace cbtl::approach {

class PreparedProgram {
 public:
  // Makes the simulator's world state the one the program's world built-ins read; returns false when the
  // state does not fit the program's scene. Empty for programs without a world.
  using WorldSync = std::function<bool(const rt::Program& program, const sim::DomainSimulator& simulator)>;

  // `path` names the program in messages; `graph` must outlive nothing: the PreparedProgram shares it.
  PreparedProgram(std::string path, std::shared_ptr<const ir::ConstraintGraph> graph, rt::Builtins builtins,
                  WorldSync worldSync = {});
  virtual ~PreparedProgram() = default;
  PreparedProgram(const PreparedProgram&) = delete;
  PreparedProgram& operator=(const PreparedProgram&) = delete;

  bool ok() const { return program_ != nullptr; }
  const std::string& errors() const { return errors_; }  // rendered diagnostics / runtime errors
  const std::string& path() const { return path_; }

  rt::Program& program() { return *program_; }
  const rt::Program& program() const { return *program_; }
  const ir::ConstraintGraph& graph() const { return *graph_; }
  // Index of a task by name; the first task when `name` is empty. -1 when there is none.
  int taskIndex(const std::string& name) const;
  const std::vector<rt::PersonalInstance>& instances(std::size_t task) const { return instances_.at(task); }
  const TaskActions& actions(std::size_t task) const { return actions_.at(task); }
  const Learner& learner() const { return *learner_; }

  // Robot domains (`world "scene.xml"`): the scene file as the caller resolved it, empty otherwise.
  const std::string& worldPath() const { return worldPath_; }
  // Runs the WorldSync (nothing without one or without a program); throws rt::RuntimeError when the state
  // does not fit the program's scene.
  void syncWorld(const sim::DomainSimulator& simulator) const;
  // The dry run's motion budgets, cheapest first (Planner.h): planner iterations per motion of a plan's dry run
  // in each tier; a request is solved with the first tier and, when that finds no solution, with the next.
  const std::vector<int>& dryRunTiers() const { return dryRunTiers_; }
  void setDryRunTiers(std::vector<int> tiers) { dryRunTiers_ = std::move(tiers); }

  // The task the simulator asks for now (DomainSimulator::requestedTask), else `configured`. Throws
  // rt::RuntimeError when the simulator names a task the program lacks.
  std::size_t taskFor(const sim::DomainSimulator& simulator, std::size_t configured) const;

 protected:
  // For subclasses that produce the graph themselves: nothing is prepared until prepare() is called.
  explicit PreparedProgram(std::string path) : path_(std::move(path)) {}
  // Prepares `graph`; on a RuntimeError, `errors()` says why and ok() stays false.
  void prepare(std::shared_ptr<const ir::ConstraintGraph> graph, rt::Builtins builtins, WorldSync worldSync);
  void setWorldPath(std::string path) { worldPath_ = std::move(path); }
  void setErrors(std::string errors) { errors_ = std::move(errors); }

 private:
  std::string path_;
  std::string worldPath_;
  std::string errors_;
  std::shared_ptr<const ir::ConstraintGraph> graph_;
  WorldSync worldSync_;
  std::unique_ptr<rt::Program> program_;
  std::vector<std::vector<rt::PersonalInstance>> instances_;
  std::vector<TaskActions> actions_;
  std::unique_ptr<Learner> learner_;
  std::vector<int> dryRunTiers_{0, 100, 1000};
};

}  // namespace cbtl::approach
