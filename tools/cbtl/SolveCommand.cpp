// `cbtl solve FILE [--task T] [--seed S] [--explain]`: one CSP of a task against the domain simulator's
// world for that seed, its solution and action plan, or why there is none. Exit codes: 0 solved, 3 no
// solution within the budget, 1 bad input, 2 usage, 70 internal error.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "app/ObservationFile.h"
#include "app/PlanReport.h"
#include "app/SolutionJson.h"
#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>

namespace {

struct SolveArgs {
  std::string file, task, csp = "exploit", profile, stdlibDir, observe, format = "text";
  std::uint64_t seed = 0;
  bool explain = false, replan = false;
  cbtl::cli::SolverArgs solver;
  cbtl::cli::TextBackendArgs text;
  cbtl::cli::ExternalSimulatorArgs external;
};

int runSolve(const SolveArgs& a, bool& statusPrinted) {
  using namespace cbtl;
  const std::optional<approach::CspChoice> choice = approach::cspChoiceNamed(a.csp);
  if (!choice) {
    fmt::print(stderr, "cbtl solve: error: unknown --csp '{}' (exploit, explore, hard)\n", a.csp);
    return 2;
  }
  const auto textBackend = cli::makeTextBackend("solve", a.text);
  if (!textBackend) return 2;
  auto lp = cli::loadForRun("solve", a.file, a.stdlibDir);
  if (!lp) return 1;
  int task = lp->taskIndex(a.task);
  if (task < 0) {
    fmt::print(stderr, "cbtl solve: error: {}: no task named '{}'\n", a.file, a.task);
    return 1;
  }
  model::UserModel user(lp->graph(), *textBackend);
  if (!a.profile.empty()) user.load(a.profile);
  sim::Observation observed;
  if (auto world = cli::simulatorFactory(*lp, a.external)({}, a.seed)) {
    lp->syncWorld(*world);
    if (a.task.empty()) task = static_cast<int>(lp->taskFor(*world, static_cast<std::size_t>(task)));
    observed = world->observe();
  } else if (lp->program().observationWidth() > 0 && a.observe.empty()) {
    fmt::print(stderr, "cbtl solve: note: no simulator for domain '{}' and no --observe file; observations are zero\n",
               lp->graph().domain);
  }
  std::vector<double> observation(lp->program().observationWidth(), 0.0);
  if (!a.observe.empty()) observed = app::readObservationFile(a.observe, lp->program(), std::move(observed));
  if (!observed.empty() || !a.observe.empty()) observation = approach::observationVector(lp->program(), observed);
  solver::Solver solver(cli::solverOptionsFor(a.solver, lp->graph().domain), approach::deriveSeed(a.seed, 1));
  const approach::Plan plan =
      approach::makePlan(*lp, static_cast<std::size_t>(task), observation, *choice, a.replan, solver, user);
  statusPrinted = true;
  if (a.format == "json") {
    fmt::print("{}\n", app::solutionJson(plan, observation));
  } else {
    app::printSolution(stdout, plan);
    if (a.explain || !plan.ok) app::printSolveStatistics(stdout, plan);
    if (a.explain) app::printObservation(stdout, lp->program(), observation);
    if (a.explain && plan.ok) app::printPersonal(stdout, plan, plan.solve.assignment);
    if (*textBackend) cli::printLlmFaults(stdout, (*textBackend)->faultReport());
    app::printRecheck(stdout, plan);
    fmt::print("status: {}\n", app::solveStatus(plan));
  }
  if (plan.refused()) {
    fmt::print(stderr,
               "cbtl solve: internal error: the solver accepted a solution that fails the independent re-check; it was "
               "refused:\n");
    for (const auto& v : plan.recheck.violations) fmt::print(stderr, "  {}\n", v);
    fmt::print(stderr, "this is a bug; please report it with the command line.\n");
    return 70;
  }
  return plan.ok ? 0 : 3;
}

void addSolve(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd =
      app.add_subcommand("solve", "solve one CSP of a task and print its solution and plan, or why there is none");
  cmd->add_option("file", args->file, "the domain's .cbtl file, or its graph from `cbtlc emit --format json`")
      ->required();
  cmd->add_option("--task", args->task, "task to solve (default: the first)");
  cmd->add_option("--seed", args->seed, "seed of the world and the solver")
      ->capture_default_str()
      ->check(cbtl::cli::unsignedIn(0));
  cmd->add_option(
         "--csp", args->csp,
         "exploit: hard + personalized constraints; explore: hard constraints, maximize entropy; hard: hard only")
      ->capture_default_str();
  cmd->add_option("--profile", args->profile, "the user profile to personalize with");
  cmd->add_option("--observe", args->observe,
                  "a JSON file of observations by name, written over the simulator's (every one, without a simulator)");
  cmd->add_option("--format", args->format, "text, or json: one cbtl-solution document (docs/runtime.md)")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  cmd->add_flag("--replan", args->replan, "if unsatisfiable, replan without personalized constraints");
  cmd->add_flag("--explain", args->explain,
                "which constraints rejected candidates, how often, and where they are declared; the personalized "
                "constraints at the solution (P, entropy, text models' context and theta)");
  cmd->add_option("--stdlib", args->stdlibDir,
                  "standard library folder (default: embedded; not used by an emitted graph)");
  cbtl::cli::addSolverOptions(cmd, args->solver);
  cbtl::cli::addTextBackendOptions(cmd, args->text);
  cbtl::cli::addExternalSimulatorOptions(cmd, args->external);
  cmd->callback([args, &exitCode]() {
    bool statusPrinted = false;
    cbtl::cli::runCommand("solve", exitCode, [&] { return runSolve(*args, statusPrinted); });
    // Every solve ends with a status a script can test, bad input included (its message is on stderr).
    if (!statusPrinted) {
      if (args->format == "json")
        fmt::print("{{\"format\": \"cbtl-solution\", \"version\": 1, \"status\": \"error\"}}\n");
      else
        fmt::print("status: error\n");
    }
  });
}

const cbtl::cli::RegisterCommand registerSolve(20, addSolve);

}  // namespace
