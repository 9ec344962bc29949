#include "LoadedProgram.h"

#include "diag/DiagnosticRenderer.h"
#include "driver/Pipeline.h"

#include <fmt/format.h>

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
    instances_.clear();
    actions_.clear();
  }
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
