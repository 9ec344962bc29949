// Approach.h — the paper's five approaches (Section 5.1, Appendix C) as the CSP each one solves.
//
//   approach            training CSP                                       learns   fallback (reference)
//   cbtl                hard constraints + max mean entropy of personal    yes      none
//   no-personalization  hard constraints only                              no       none
//   free-explore        hard constraints only                              yes      none
//   exploit-only        hard + personal constraints                        yes      replan without personal
//   epsilon-greedy      with probability epsilon free-explore, else exploit yes      replan without personal
//
// Evaluation always solves hard + personal constraints with no cost (exploit what was learned).
// `--replan` gives every approach the paper's recourse: when the full CSP is unsatisfiable, replan
// without the personalized constraints and tell the user.
// Epsilon-greedy's coin comes from the run's RNG, one draw per CSP (the reference re-seeded its generator
// on every call, so in one domain its coin always came up "exploit"; see docs/runtime.md).
#pragma once

#include "runtime/core/Rng.h"
#include "runtime/solver/Csp.h"

#include <optional>
#include <string>
#include <vector>

namespace cbtl::approach {

enum class ApproachKind { Cbtl, NoPersonalization, FreeExplore, ExploitOnly, EpsilonGreedy };

const char* toString(ApproachKind k);
std::optional<ApproachKind> parseApproach(const std::string& name);
const std::vector<std::string>& approachNames();

struct ApproachConfig {
  ApproachKind kind = ApproachKind::Cbtl;
  double epsilon = 0.5;
  bool replan = false;  // the paper's recourse for every approach
};

struct CspChoice {
  solver::PersonalMode personal = solver::PersonalMode::Exclude;
  solver::CostKind cost = solver::CostKind::None;
};

// What the approach solves for a training request; draws epsilon-greedy's coin from `rng`.
CspChoice trainingChoice(const ApproachConfig& config, rt::Rng& rng);
// What every approach solves in evaluation.
CspChoice evaluationChoice();
// The CSPs a person may ask for by name: "exploit" (hard + personalized constraints, evaluation's), "explore"
// (hard constraints, maximum entropy: CBTL's exploration), "hard" (hard constraints only); nullopt for other names.
std::optional<CspChoice> cspChoiceNamed(const std::string& name);
bool learns(const ApproachConfig& config);
// Whether a failed full CSP is re-solved without the personalized constraints.
bool fallsBack(const ApproachConfig& config);

}  // namespace cbtl::approach
