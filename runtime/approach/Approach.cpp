#include "runtime/approach/Approach.h"

namespace cbtl::approach {

const char* toString(ApproachKind k) {
  switch (k) {
    case ApproachKind::Cbtl:
      return "cbtl";
    case ApproachKind::NoPersonalization:
      return "no-personalization";
    case ApproachKind::FreeExplore:
      return "free-explore";
    case ApproachKind::ExploitOnly:
      return "exploit-only";
    case ApproachKind::EpsilonGreedy:
      return "epsilon-greedy";
  }
  return "?";
}

const std::vector<std::string>& approachNames() {
  static const std::vector<std::string> names = {"cbtl", "no-personalization", "free-explore", "exploit-only",
                                                 "epsilon-greedy"};
  return names;
}

std::optional<ApproachKind> parseApproach(const std::string& name) {
  for (auto k : {ApproachKind::Cbtl, ApproachKind::NoPersonalization, ApproachKind::FreeExplore,
                 ApproachKind::ExploitOnly, ApproachKind::EpsilonGreedy}) {
    if (name == toString(k)) return k;
  }
  return std::nullopt;
}

CspChoice trainingChoice(const ApproachConfig& config, rt::Rng& rng) {
  using solver::CostKind;
  using solver::PersonalMode;
  switch (config.kind) {
    case ApproachKind::Cbtl:
      return {PersonalMode::Exclude, CostKind::Entropy};
    case ApproachKind::NoPersonalization:
    case ApproachKind::FreeExplore:
      return {PersonalMode::Exclude, CostKind::Declared};
    case ApproachKind::ExploitOnly:
      return {PersonalMode::Include, CostKind::Declared};
    case ApproachKind::EpsilonGreedy:
      if (rng.uniform() < config.epsilon) return {PersonalMode::Exclude, CostKind::Declared};
      return {PersonalMode::Include, CostKind::Declared};
  }
  return {};
}

CspChoice evaluationChoice() { return {solver::PersonalMode::Include, solver::CostKind::Declared}; }

std::optional<CspChoice> cspChoiceNamed(const std::string& name) {
  if (name == "exploit") return evaluationChoice();
  if (name == "explore") return CspChoice{solver::PersonalMode::Exclude, solver::CostKind::Entropy};
  if (name == "hard") return CspChoice{solver::PersonalMode::Exclude, solver::CostKind::Declared};
  return std::nullopt;
}

bool learns(const ApproachConfig& config) { return config.kind != ApproachKind::NoPersonalization; }

bool fallsBack(const ApproachConfig& config) {
  return config.replan || config.kind == ApproachKind::ExploitOnly || config.kind == ApproachKind::EpsilonGreedy;
}

}  // namespace cbtl::approach
