#include "app/RunFailures.h"

#include <fmt/format.h>

namespace cbtl::app {

PhaseFailures phaseFailures(const std::string& phase, const approach::Competence& c) {
  PhaseFailures f;
  f.phase = phase;
  f.requests = c.requests;
  f.unsolved = c.requests - c.solved;
  f.failedExecution = c.failed;
  f.caregiverResets = c.caregiverResets;
  return f;
}

PhaseFailures evaluationFailures(const std::string& phase, const approach::Competence& c) {
  PhaseFailures f = phaseFailures(phase, c);
  f.requests = c.executed + c.failed;  // the solved plans that were carried out
  f.unsolved = 0;
  return f;
}

std::vector<PhaseFailures> phasesAbove(const std::vector<PhaseFailures>& phases, double maxRate) {
  std::vector<PhaseFailures> above;
  for (const PhaseFailures& p : phases) {
    if (p.requests > 0 && p.rate() > maxRate) above.push_back(p);
  }
  return above;
}

std::string failureWarning(const std::string& command, const std::string& file, const std::vector<PhaseFailures>& above,
                           double maxRate) {
  if (above.empty()) return {};
  std::string text;
  bool unsolved = false, failedExecution = false, resets = false;
  for (const PhaseFailures& p : above) {
    text += fmt::format(
        "cbtl {}: warning: {} of {} {} requests failed ({:.1f} %, above --max-failure-rate {:g} %): {} not solved "
        "within budget, {} failed in execution{}\n",
        command, p.failures(), p.requests, p.phase, 100 * p.rate(), 100 * maxRate, p.unsolved, p.failedExecution,
        p.caregiverResets > 0 ? fmt::format(", {} caregiver resets", p.caregiverResets) : std::string());
    unsolved = unsolved || p.unsolved > 0;
    failedExecution = failedExecution || p.failedExecution > 0;
    resets = resets || p.caregiverResets > 0;
  }
  if (unsolved) {
    text += fmt::format(
        "  not solved: `cbtl solve {} --explain` names the constraints that reject candidates and the variables no "
        "sampler changes (cbtlc's W0503); a simulator whose training world stays finished or stuck looks the same: "
        "world 0 is reset once, when the run starts, and after `done` the simulator must begin the next task itself "
        "(docs/simulator-protocol.md)\n",
        file);
  }
  if (failedExecution) {
    text +=
        "  failed in execution: the world refused a solved plan's action (no IK, no path, an ignored call); the "
        "run's motions.jsonl and `cbtl audit` show what the robot did\n";
  }
  if (resets) text += "  caregiver resets: the robot stood idle (nothing solvable) until a person put it back\n";
  text += "  this is not an ordinary result, so the command exits 3; --max-failure-rate 1 accepts any failures\n";
  return text;
}

}  // namespace cbtl::app
