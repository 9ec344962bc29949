// `cbtl solve FILE [--task T] [--seed S] [--explain]`: one CSP of a task against the domain simulator's
// world for that seed, its solution and action plan, or why there is none. Exit codes: 0 solved, 3 no
// solution within the budget, 1 bad input, 2 usage, 70 internal error.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/PersonalExplanation.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>

namespace {

struct SolveArgs {
  std::string file, task, csp = "exploit", profile, stdlibDir;
  std::uint64_t seed = 0;
  bool explain = false, replan = false;
  cbtl::cli::SolverArgs solver;
  cbtl::cli::TextBackendArgs text;
};

std::string renderCall(const cbtl::sim::ActionCall& c) {
  std::string s = c.name + "(";
  for (std::size_t i = 0; i < c.args.size(); ++i) {
    const auto& a = c.args[i];
    if (i) s += ", ";
    if (a.kind == cbtl::sim::Value::Kind::Name)
      s += a.text;
    else if (a.kind == cbtl::sim::Value::Kind::Number)
      s += fmt::format("{:.6g}", a.number);
    else {
      s += "(";
      for (std::size_t k = 0; k < a.vector.size(); ++k) s += fmt::format("{}{:.6g}", k ? ", " : "", a.vector[k]);
      s += ")";
    }
  }
  return s + ")";
}

void explain(const cbtl::approach::Plan& plan) {
  using namespace cbtl::solver;
  auto print = [&](const Csp& csp, const SolveResult& r, const char* title) {
    fmt::print("{}: {} after {} iterations ({} candidates checked, {} pruned by cost, {} improvements)\n", title,
               toString(r.outcome), r.iterations, r.candidatesChecked, r.prunedByCost, r.improvements);
    std::vector<ConstraintStats> stats = r.constraints;
    std::stable_sort(stats.begin(), stats.end(),
                     [](const auto& a, const auto& b) { return a.rejections > b.rejections; });
    fmt::print("  {:>10} {:>11}  {:<48} {}\n", "rejected", "evaluated", "constraint", "declared at");
    for (const auto& s : stats) {
      if (s.evaluations == 0 && s.rejections == 0) continue;
      fmt::print("  {:>10} {:>11}  {:<48} {}\n", s.rejections, s.evaluations, constraintName(csp, s.ref),
                 constraintLocation(csp, s.ref));
    }
    if (!r.planFailures.empty()) {
      std::vector<std::pair<std::string, PlanFailure>> failures(r.planFailures.begin(), r.planFailures.end());
      std::stable_sort(failures.begin(), failures.end(),
                       [](const auto& a, const auto& b) { return a.second.count > b.second.count; });
      fmt::print("  {} rejections by failing action (the first detail of each):\n", kPlanExecutesName);
      for (const auto& [what, f] : failures)
        fmt::print("  {:>10}  {}{}\n", f.count, what, f.example.empty() ? "" : " (" + f.example + ")");
    }
  };
  for (const auto& [budget, result] : plan.failedTiers)
    print(plan.csp, result, fmt::format("dry-run tier with {} planner iterations per motion", budget).c_str());
  if (plan.dryRun())
    fmt::print("dry-run tier of the result: {} planner iterations per motion\n", plan.motionIterations);
  if (plan.failedFull) print(plan.csp, *plan.failedFull, "with personalized constraints");
  print(plan.csp, plan.solve, plan.failedFull ? "replanned without personalized constraints" : "solve");
  if (!plan.dryRun() && plan.csp.program->host() != nullptr && plan.csp.program->host()->executionModel() != nullptr)
    fmt::print("note: the plan was not dry-run: the world model does not know every action of the task\n");
}

// What the CSP was solved against: every observation, a set as the members it holds.
void explainObservation(const cbtl::rt::Program& program, const std::vector<double>& observation) {
  if (program.observationSlots().empty()) return;
  fmt::print("observed:\n");
  for (const auto& [name, slot] : program.observationSlots()) {
    if (slot.offset + slot.type.width > observation.size()) continue;
    const double* v = observation.data() + slot.offset;
    std::string text;
    if (slot.type.kind == cbtl::rt::ValueKind::Set) {
      const cbtl::rt::ValueType element = program.setElementType(slot.type);
      for (std::size_t i = 0; i < program.setElementCount(slot.type); ++i) {
        const double member = static_cast<double>(i);
        if (v[i] != 0) text += (text.empty() ? "" : ", ") + program.render(element, &member);
      }
      text = "{" + text + "}";
    } else {
      text = program.render(slot.type, v);
    }
    fmt::print("  {} = {}\n", name, text);
  }
}

// The personalized constraints at the chosen assignment: P(holds) against accept, entropy, and what each text
// model was asked (subject, context) and has learned (theta).
void explainPersonal(const cbtl::approach::Plan& plan) {
  const auto instances = cbtl::solver::explainPersonal(plan.csp, plan.solve.assignment);
  if (instances.empty()) return;
  fmt::print("personalized constraints at the solution:\n");
  fmt::print("  {:<8} {:>7} {:>7} {:>8}  {}\n", "", "P", "accept", "entropy", "instance");
  for (const auto& e : instances) {
    const char* status = !e.applies ? "n/a" : e.holds ? "holds" : "fails";
    fmt::print("  {:<8} {:>7.3f} {:>7.3f} {:>8.3f}  {}{}{}\n", status, e.probability, e.accept, e.entropyBits, e.name,
               e.key.empty() ? "" : " [" + e.key + "]", e.inCsp ? "" : " (not in this CSP)");
    for (const auto& t : e.text) {
      fmt::print("           {} = {}{}\n", t.factor, t.subject, t.context.empty() ? "" : " in " + t.context);
      fmt::print("           theta: {}\n", t.theta);
    }
  }
}

int runSolve(const SolveArgs& a) {
  using namespace cbtl;
  approach::CspChoice choice;
  if (a.csp == "exploit")
    choice = approach::evaluationChoice();
  else if (a.csp == "explore")
    choice = {solver::PersonalMode::Exclude, solver::CostKind::Entropy};
  else if (a.csp == "hard")
    choice = {solver::PersonalMode::Exclude, solver::CostKind::Declared};
  else {
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
  std::vector<double> observation(lp->program().observationWidth(), 0.0);
  if (auto world = domains::createSimulator(lp->graph().domain, app::simulatorFacts(*lp), {}, a.seed)) {
    lp->syncWorld(*world);
    if (a.task.empty()) task = static_cast<int>(lp->taskFor(*world, static_cast<std::size_t>(task)));
    observation = approach::observationVector(lp->program(), world->observe());
  } else if (lp->program().observationWidth() > 0) {
    fmt::print(stderr, "cbtl solve: note: no simulator for domain '{}'; observations are zero\n", lp->graph().domain);
  }
  solver::Solver solver(cli::solverOptionsFor(a.solver, lp->graph().domain), approach::deriveSeed(a.seed, 1));
  const approach::Plan plan =
      approach::makePlan(*lp, static_cast<std::size_t>(task), observation, choice, a.replan, solver, user);
  const auto& program = lp->program();
  const ir::Task& t = lp->graph().tasks[static_cast<std::size_t>(task)];
  fmt::print(
      "task {}: {}{}\n", t.name, solver::toString(plan.solve.outcome),
      plan.replanned ? " (replanned without personalized constraints: the user's preferences cannot be met)" : "");
  if (plan.ok) {
    for (ir::VarId v : t.vars) {
      const auto& slot = program.slot(v);
      fmt::print("  {} = {}\n", lp->graph().variables[v].name,
                 program.render(slot.type, plan.solve.assignment.data() + slot.offset));
    }
    fmt::print("plan ({} calls):\n", plan.calls.size());
    for (const auto& c : plan.calls) fmt::print("  {}\n", renderCall(c));
  }
  if (a.explain || !plan.ok) explain(plan);
  if (a.explain) explainObservation(program, observation);
  if (a.explain && plan.ok) explainPersonal(plan);
  if (*textBackend) cli::printLlmFaults(stdout, (*textBackend)->faultReport());
  if (plan.rechecked) {
    fmt::print("re-check: {} constraints and {} variables evaluated from scratch: {}\n",
               plan.recheck.constraintsChecked, plan.recheck.variablesChecked,
               plan.recheck.holds() ? "all hold" : "VIOLATED");
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
  cmd->add_flag("--replan", args->replan, "if unsatisfiable, replan without personalized constraints");
  cmd->add_flag("--explain", args->explain,
                "which constraints rejected candidates, how often, and where they are declared; the personalized "
                "constraints at the solution (P, entropy, text models' context and theta)");
  cmd->add_option("--stdlib", args->stdlibDir,
                  "standard library folder (default: embedded; not used by an emitted graph)");
  cbtl::cli::addSolverOptions(cmd, args->solver);
  cbtl::cli::addTextBackendOptions(cmd, args->text);
  cmd->callback([args, &exitCode]() { cbtl::cli::runCommand("solve", exitCode, [&] { return runSolve(*args); }); });
}

const cbtl::cli::RegisterCommand registerSolve(20, addSolve);

}  // namespace
