#include "tools/cbtl/TrialPool.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

namespace cbtl::cli {

namespace {

TrialOutcome runOne(const app::LoadedProgram& lp, const approach::SimulatorFactory& factory,
                    const approach::ExperimentConfig& config) {
  TrialOutcome out;
  const auto start = std::chrono::steady_clock::now();
  try {
    out.result = approach::runExperiment(lp, factory, config);
  } catch (...) {
    out.error = std::current_exception();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!out.error && out.result.finishedEarlier) {
    out.finishedEarlier = true;
    out.seconds = out.result.recordedSeconds.value_or(0);  // 0: not recorded (the table shows no time for it)
  }
  return out;
}

}  // namespace

std::vector<TrialOutcome> runTrials(const app::LoadedProgram& program, const std::string& file,
                                    const std::string& stdlibDir, const TextBackendArgs& text,
                                    const ExternalSimulatorArgs& external,
                                    std::vector<approach::ExperimentConfig> trials, int jobs,
                                    const std::function<void(std::size_t, const TrialOutcome&)>& onDone) {
  std::vector<TrialOutcome> outcomes(trials.size());
  std::mutex doneMutex;
  const auto finish = [&](std::size_t i, TrialOutcome o) {
    std::lock_guard lock(doneMutex);
    outcomes[i] = std::move(o);
    onDone(i, outcomes[i]);
  };
  jobs = std::max(1, std::min<int>(jobs, static_cast<int>(trials.size())));
  if (jobs == 1) {
    const approach::SimulatorFactory factory = simulatorFactory(program, external);
    for (std::size_t i = 0; i < trials.size(); ++i) finish(i, runOne(program, factory, trials[i]));
    return outcomes;
  }
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    // Everything a trial touches is this worker's own: the program, its world, the simulators, the backend.
    std::unique_ptr<app::LoadedProgram> lp;
    std::exception_ptr loadError;
    try {
      lp = app::LoadedProgram::load(file, stdlibDir);
      if (!lp->ok()) throw std::runtime_error("the program cannot be loaded again: " + lp->errors());
    } catch (...) {
      loadError = std::current_exception();
    }
    const auto backend = makeTextBackend("experiment", text);
    const approach::SimulatorFactory factory =
        lp && lp->ok() ? simulatorFactory(*lp, external) : approach::SimulatorFactory{};
    for (std::size_t i = next++; i < trials.size(); i = next++) {
      if (loadError || !backend) {
        TrialOutcome failed;
        failed.error =
            loadError ? loadError : std::make_exception_ptr(std::runtime_error("the text backend cannot be made"));
        finish(i, std::move(failed));
        continue;
      }
      approach::ExperimentConfig config = trials[i];
      config.textBackend = *backend;
      finish(i, runOne(*lp, factory, config));
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  return outcomes;
}

}  // namespace cbtl::cli
