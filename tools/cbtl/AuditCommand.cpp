// `cbtl audit RUN...`: re-checks every motion the runs recorded (app/audit/MotionAudit.h) and prints, per run, the
// motions, segments and states checked, every violation (the first 20 listed, or --list N), and the closest approach to
// each body class, the program's clearances first. Exit codes: 0 every run passed, 1 a violation or a run that cannot
// be audited, 2 usage, 70 internal error.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/OptionChecks.h"

#include "app/audit/MotionAudit.h"

#include <fmt/core.h>

#include <memory>
#include <string>
#include <vector>

namespace {

struct AuditArgs {
  std::vector<std::string> runs;
  cbtl::app::AuditOptions options;
};

void printReport(const cbtl::app::AuditReport& r) {
  if (!r.error.empty()) {
    fmt::print("{}: cannot audit: {}\n", r.run, r.error);
    return;
  }
  fmt::print("{}: {} motions, {} segments, {} states checked: {}\n", r.run, r.motions, r.segments, r.states,
             r.passed() ? "no violation" : fmt::format("{} violations", r.violationCount));
  if (r.continuityChecked)
    fmt::print(
        "  record: every motion starts where the robot was left{}; {} plans, {} accepted by a dry run, {} of "
        "those rejected here\n",
        r.gaps == 0 ? "" : fmt::format(" except {} (violations)", r.gaps), r.plans, r.dryRunPlans,
        r.dryRunPlansRejected);
  else
    fmt::print("  record: marks no plans or resets (written before they were recorded): continuity not checked\n");
  for (const auto& v : r.violations)
    fmt::print("  violation: {}: {} / {} {:.6f} m apart, {:.4f} m required\n", v.where, v.first, v.second, v.separation,
               v.required);
  for (const std::string& cls : r.classes) {
    const auto it = r.closest.find(cls);
    if (it == r.closest.end()) continue;
    fmt::print("  closest to {}: {:.6f} m ({} / {}), at {}\n", cls, it->second.distance, it->second.first,
               it->second.second, it->second.where);
  }
}

int runAudit(const AuditArgs& a) {
  int failures = 0;
  for (const std::string& run : a.runs) {
    const cbtl::app::AuditReport r = cbtl::app::auditRun(run, a.options);
    printReport(r);
    if (!r.passed()) ++failures;
  }
  fmt::print("audited {} runs: {} passed, {} failed\n", a.runs.size(), a.runs.size() - failures, failures);
  return failures == 0 ? 0 : 1;
}

}  // namespace

void addAuditCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<AuditArgs>();
  CLI::App* cmd = app.add_subcommand("audit", "Re-check every motion that runs recorded, independently of the planner");
  cmd->add_option("runs", args->runs, "run folders (cbtl run --out, or a trial folder of cbtl experiment)")->required();
  cmd->add_option("--resolution", args->options.resolution,
                  "largest step between checked states along a segment (rad for joints and yaw, m for the base)")
      ->check(cbtl::cli::realIn(1e-5, 0.1));
  cmd->add_option("--cap", args->options.cap, "distances up to this are measured for the clearance report (m)")
      ->check(cbtl::cli::realIn(0, 10));
  cmd->add_flag(
      "--every-pair", [args](std::int64_t) { args->options.skipFarPairs = false; },
      "measure every candidate pair at every state, also where a distance bound shows it cannot matter "
      "(slower; the same report)");
  cmd->add_option("--list", args->options.listed, "violations to list per run (all are counted; default 20)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--program", args->options.program, "the runs' .cbtl file (default: each run's config.json)");
  cmd->callback([args, &exitCode] { cbtl::cli::runCommand("audit", exitCode, [&] { return runAudit(*args); }); });
}

static cbtl::cli::RegisterCommand reg(55, addAuditCommand);
