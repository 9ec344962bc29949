#include "runtime/approach/PreparedProgram.h"

#include "runtime/sim/DomainSimulator.h"

#include <fmt/format.h>

namespace cbtl::approach {

PreparedProgram::PreparedProgram(std::string path, std::shared_ptr<const ir::ConstraintGraph> graph,
                                 rt::Builtins builtins, WorldSync worldSync)
    : path_(std::move(path)) {
  prepare(std::move(graph), std::move(builtins), std::move(worldSync));
}

void PreparedProgram::prepare(std::shared_ptr<const ir::ConstraintGraph> graph, rt::Builtins builtins,
                              WorldSync worldSync) {
  graph_ = std::move(graph);
  worldSync_ = std::move(worldSync);
  try {
    auto program = std::make_unique<rt::Program>(*graph_, std::move(builtins));
    for (const auto& task : graph_->tasks) {
      instances_.push_back(rt::personalize(*program, task));
      actions_.emplace_back(*program, task);
    }
    learner_ = std::make_unique<Learner>(*program);
    program_ = std::move(program);
  } catch (const rt::RuntimeError& e) {
    errors_ = fmt::format("error: {}\n", e.what());
    instances_.clear();
    actions_.clear();
  }
}

void PreparedProgram::syncWorld(const sim::DomainSimulator& simulator) const {
  if (!worldSync_ || program_ == nullptr) return;
  if (!worldSync_(*program_, simulator)) {
    throw rt::RuntimeError("", fmt::format("the simulator's world state does not fit the scene '{}'", worldPath_));
  }
}

std::size_t PreparedProgram::taskFor(const sim::DomainSimulator& simulator, std::size_t configured) const {
  const std::string name = simulator.requestedTask();
  if (name.empty()) return configured;
  const int t = taskIndex(name);
  if (t < 0)
    throw rt::RuntimeError("",
                           fmt::format("the simulator asks for task '{}', which '{}' does not declare", name, path_));
  return static_cast<std::size_t>(t);
}

int PreparedProgram::taskIndex(const std::string& name) const {
  if (graph_ == nullptr) return -1;
  const auto& tasks = graph_->tasks;
  if (tasks.empty()) return -1;
  if (name.empty()) return 0;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (tasks[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace cbtl::approach
