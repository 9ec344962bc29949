// app/RunFailures.h: which phases failed too often, and a warning that names what the counts show.
#include "app/RunFailures.h"

#include <gtest/gtest.h>

namespace {

using cbtl::app::failureWarning;
using cbtl::app::phaseFailures;
using cbtl::app::phasesAbove;

cbtl::approach::Competence competence(std::int64_t requests, std::int64_t solved, std::int64_t executed,
                                      std::int64_t failed, std::int64_t resets = 0) {
  cbtl::approach::Competence c;
  c.requests = requests;
  c.solved = solved;
  c.executed = executed;
  c.failed = failed;
  c.caregiverResets = resets;
  return c;
}

TEST(RunFailures, CountsUnsolvedAndFailedExecutionAsFailures) {
  const auto f = phaseFailures("training", competence(300, 2, 1, 1, 59));
  EXPECT_EQ(f.unsolved, 298);
  EXPECT_EQ(f.failedExecution, 1);
  EXPECT_EQ(f.failures(), 299);
  EXPECT_NEAR(f.rate(), 299.0 / 300.0, 1e-12);
  // A solved plan with no calls is neither executed nor failed: not a failure.
  EXPECT_EQ(phaseFailures("evaluation", competence(10, 10, 9, 0)).failures(), 0);
}

// Evaluation's unsolved requests are an outcome (preferences no plan meets), not a stuck run: only its plans that
// failed in execution count, out of the plans carried out.
TEST(RunFailures, EvaluationCountsOnlyPlansThatFailedInExecution) {
  const auto f = cbtl::app::evaluationFailures("evaluation", competence(100, 60, 57, 3));
  EXPECT_EQ(f.unsolved, 0);
  EXPECT_EQ(f.failedExecution, 3);
  EXPECT_EQ(f.requests, 60);
  EXPECT_NEAR(f.rate(), 0.05, 1e-12);
}

TEST(RunFailures, OnlyPhasesStrictlyAboveTheRateAreReported) {
  const std::vector<cbtl::app::PhaseFailures> phases = {phaseFailures("training", competence(100, 90, 90, 0)),
                                                        phaseFailures("evaluation", competence(100, 89, 89, 0)),
                                                        phaseFailures("nothing asked", competence(0, 0, 0, 0))};
  const auto above = phasesAbove(phases, 0.10);
  ASSERT_EQ(above.size(), 1u);
  EXPECT_EQ(above[0].phase, "evaluation");
  EXPECT_TRUE(phasesAbove(phases, 1.0).empty());
  EXPECT_EQ(phasesAbove(phases, 0.0).size(), 2u);
}

TEST(RunFailures, WarningNamesTheCausesTheCountsShow) {
  const auto stuck = phasesAbove({phaseFailures("training", competence(300, 2, 2, 0))}, 0.10);
  const std::string w = failureWarning("run", "plants.cbtl", stuck, 0.10);
  EXPECT_NE(w.find("cbtl run: warning: 298 of 300 training requests failed (99.3 %"), std::string::npos) << w;
  EXPECT_NE(w.find("`cbtl solve plants.cbtl --explain`"), std::string::npos) << w;
  EXPECT_NE(w.find("world 0 is reset once"), std::string::npos) << w;
  EXPECT_EQ(w.find("failed in execution:"), std::string::npos) << w;  // no execution failed
  EXPECT_NE(w.find("exits 3"), std::string::npos) << w;

  const auto refused = phasesAbove({phaseFailures("evaluation", competence(10, 10, 4, 6))}, 0.10);
  const std::string v = failureWarning("experiment", "x.cbtl", refused, 0.10);
  EXPECT_NE(v.find("failed in execution:"), std::string::npos) << v;
  EXPECT_EQ(v.find("not solved:"), std::string::npos) << v;
  EXPECT_TRUE(failureWarning("run", "x.cbtl", {}, 0.10).empty());
}

}  // namespace
