// Across every domain and every approach, short trials re-check every plan they execute and the re-check
// never refuses one: the solver's acceptance and the independent check agree.
#include "tests/unit/runtime/TestPrograms.h"

#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/Experiment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>

using namespace cbtl;

namespace {

using Case = std::tuple<const char*, approach::ApproachKind>;

class RecheckEverywhere : public ::testing::TestWithParam<Case> {};

std::string caseName(const ::testing::TestParamInfo<Case>& param) {
  std::string file = std::get<0>(param.param);
  std::string name = file.substr(1, file.find('/', 1) - 1) + "_" + approach::toString(std::get<1>(param.param));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace

TEST_P(RecheckEverywhere, EveryExecutedPlanIsRecheckedAndNoneIsRefused) {
  const auto [file, kind] = GetParam();
  auto lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + file);
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const std::string domain = lp->graph().domain;
  approach::ExperimentConfig c;
  c.approach.kind = kind;
  c.seed = 1;
  const bool robot = domain != "cooking";
  c.steps = robot ? 3 : 300;
  c.evalEvery = c.steps;
  c.evalTasks = 1;
  c.maxEvalEpisodeSteps = robot ? 3 : 100;
  // Much smaller than the reference's robot budgets: the point is the re-check, not the outcome.
  c.solverOptions.maxIters = robot ? 300 : 100000;
  c.solverOptions.numImprovements = robot ? 5 : 500;
  c.solverOptions.maxImprovementAttempts = robot ? 10 : 10000;
  const auto factory = [domain, facts = app::simulatorFacts(*lp)](const sim::SimulatorOptions& o, std::uint64_t seed) {
    return domains::createSimulator(domain, facts, o, seed);
  };
  const auto r = approach::runExperiment(*lp, factory, c);
  EXPECT_EQ(r.recheckViolations, 0) << r.firstRecheckViolation;
  EXPECT_GT(r.rechecks, 0) << "no plan was solved, so nothing was re-checked";
}

// Every approach in Cooking, Cleaning and Feeding. Books solves for seconds per CSP (the robot-execution issue),
// so it runs the two approaches that between them build every kind of CSP: CBTL (exploration with the entropy
// cost, exploitation with the personalized constraints) and No Personalization (hard constraints only).
const auto kEveryApproach = ::testing::Values(approach::ApproachKind::Cbtl, approach::ApproachKind::NoPersonalization,
                                              approach::ApproachKind::FreeExplore, approach::ApproachKind::ExploitOnly,
                                              approach::ApproachKind::EpsilonGreedy);
INSTANTIATE_TEST_SUITE_P(EveryApproach, RecheckEverywhere,
                         ::testing::Combine(::testing::Values("/cooking/cooking.cbtl", "/cleaning/cleaning.cbtl",
                                                              "/feeding/feeding.cbtl"),
                                            kEveryApproach),
                         caseName);
INSTANTIATE_TEST_SUITE_P(Books, RecheckEverywhere,
                         ::testing::Combine(::testing::Values("/books/books.cbtl"),
                                            ::testing::Values(approach::ApproachKind::Cbtl,
                                                              approach::ApproachKind::NoPersonalization)),
                         caseName);
