// The learned models: interval (exact trapezoid), threshold, table, entropy, products of factors.
#include "runtime/model/Entropy.h"
#include "runtime/model/Factor.h"
#include "runtime/model/IntervalModel.h"
#include "runtime/model/ModelSummary.h"
#include "runtime/model/TableModel.h"
#include "runtime/model/ThresholdModel.h"

#include <gtest/gtest.h>

using namespace cbtl::model;

TEST(IntervalModel, ReferenceVector) {
  IntervalModel m(0, 1);
  m.observe(0.2, false);
  m.observe(0.4, true);
  m.observe(0.6, true);
  m.observe(0.8, false);
  EXPECT_NEAR(m.probability(0.1), 0.0, 1e-12);
  EXPECT_NEAR(m.probability(0.3), 0.5, 1e-12);
  EXPECT_NEAR(m.probability(0.5), 1.0, 1e-12);
  EXPECT_NEAR(m.probability(0.7), 0.5, 1e-12);
  EXPECT_NEAR(m.probability(0.9), 0.0, 1e-12);
}

TEST(IntervalModel, PriorAcceptsTheWholeKnownRangeWithNoUncertainty) {
  IntervalModel m(2.5, 3.5);
  for (double x : {2.5, 3.0, 3.5}) {
    EXPECT_EQ(m.probability(x), 1.0) << x;
    EXPECT_EQ(bernoulliEntropyBits(m.probability(x)), 0.0);
  }
  EXPECT_EQ(m.probability(2.4), 0.0);
  EXPECT_EQ(m.probability(3.6), 0.0);
  m.observe(3.4, false);  // negatives alone do not move the prior (as in the reference)
  EXPECT_EQ(m.probability(3.45), 1.0);
}

TEST(IntervalModel, EntropyIsMaximalAtTheRampMidpoints) {
  IntervalModel m(0, 1);
  m.observe(0.2, false);
  m.observe(0.4, true);
  m.observe(0.6, true);
  m.observe(0.8, false);
  EXPECT_NEAR(bernoulliEntropyBits(m.probability(0.3)), 1.0, 1e-12);
  EXPECT_LT(bernoulliEntropyBits(m.probability(0.25)), 1.0);
  EXPECT_EQ(bernoulliEntropyBits(m.probability(0.5)), 0.0);
}

TEST(IntervalModel, PosteriorIsTheTrapezoidOnceAPositiveIsKnown) {
  IntervalModel m(0, 1);
  m.observe(0.2, false);
  m.observe(0.4, true);
  m.observe(0.8, false);
  for (int i = -10; i <= 110; ++i) EXPECT_EQ(m.posterior(i / 100.0), m.probability(i / 100.0)) << i;
}

TEST(IntervalModel, PosteriorBeforeTheFirstPositiveIsUncertainAndZeroAtNegatives) {
  // Uniform prior over the intervals 0 <= a <= b <= 1: P(a <= x <= b) = 2 x (1 - x), at most 1/2.
  IntervalModel m(0, 1);
  EXPECT_NEAR(m.posterior(0.5), 0.5, 1e-12);
  EXPECT_NEAR(m.posterior(0.25), 2 * 0.25 * 0.75, 1e-12);
  EXPECT_EQ(m.posterior(0.0), 0.0);
  EXPECT_EQ(m.posterior(1.2), 0.0);
  EXPECT_EQ(m.probability(0.25), 1.0) << "the constraint stays optimistic";
  // A negative at 0.5: the interval lies in [0, 0.5] or in [0.5, 1]; each gap's mass is 0.5^2 / 2.
  m.observe(0.5, false);
  EXPECT_EQ(m.posterior(0.5), 0.0) << "a refused value is never uncertain again";
  EXPECT_NEAR(m.posterior(0.25), 0.25 * 0.25 / 0.25, 1e-12);
  EXPECT_NEAR(m.posterior(0.75), 0.25, 1e-12);
  EXPECT_EQ(m.probability(0.5), 0.0) << "nor offered again before anything is liked";
  // Entropy now leads away from the refused value, towards the middles of the gaps.
  EXPECT_GT(bernoulliEntropyBits(m.posterior(0.25)), bernoulliEntropyBits(m.posterior(0.45)));
  // Negatives outside the bounds, or repeated, change nothing.
  IntervalModel n(0, 1);
  n.observe(0.5, false);
  n.observe(0.5, false);
  n.observe(1.5, false);
  EXPECT_NEAR(n.posterior(0.25), 0.25, 1e-12);
  n.observe(0.3, true);
  EXPECT_EQ(n.posterior(0.3), 1.0);
}

TEST(IntervalModel, BeforeTheFirstPositiveARefusedValueAndItsNeighbourhoodAreNotAccepted) {
  IntervalModel m(0, 1.25);  // Books' range of motion: the radius is 1 % of 1.25 m = 12.5 mm
  m.observe(0.4158, false);
  EXPECT_EQ(m.probability(0.4158), 0.0);
  EXPECT_EQ(m.probability(0.4158 + 0.0009), 0.0) << "the same spot, up to an IK tolerance";
  EXPECT_EQ(m.probability(0.4158 - 0.012), 0.0);
  EXPECT_EQ(m.probability(0.4158 + 0.013), 1.0) << "a new value";
  EXPECT_EQ(m.probability(0.4158 - 0.013), 1.0);
  m.observe(0.9, false);  // the nearest negative decides, on either side
  EXPECT_EQ(m.probability(0.895), 0.0);
  EXPECT_EQ(m.probability(0.65), 1.0);
  // Negatives outside the bounds refuse nothing inside them.
  IntervalModel n(0, 1);
  n.observe(1.005, false);
  EXPECT_EQ(n.probability(1.0), 1.0);
  // Once something is liked the trapezoid decides: a negative far outside the positives only bounds the ramp.
  m.observe(0.2, true);
  EXPECT_EQ(m.probability(0.2), 1.0);
  EXPECT_GT(m.probability(0.41), 0.0);
}

TEST(IntervalModel, StaysInUnitIntervalOnInconsistentData) {
  IntervalModel m(0, 1);
  m.observe(0.5, true);
  m.observe(0.5, false);
  m.observe(0.3, true);
  m.observe(0.4, false);  // between two positives: contradicts them
  m.observe(0.9, true);
  m.observe(0.1, false);
  for (int i = -10; i <= 110; ++i) {
    const double p = m.probability(i / 100.0);
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
  }
  EXPECT_LE(m.x1(), m.x2());
  EXPECT_LE(m.x2(), m.x3());
  EXPECT_LE(m.x3(), m.x4());
}

TEST(IntervalModel, ResetForgetsEverything) {
  IntervalModel m(0, 1);
  m.observe(0.5, true);
  m.observe(0.7, false);
  m.reset();
  EXPECT_TRUE(m.data().empty());
  EXPECT_EQ(m.probability(0.8), 1.0);
}

TEST(ThresholdModel, AboveNarrowsAndInterpolates) {
  ThresholdModel m(0, 1, ThresholdModel::Direction::Above);
  EXPECT_NEAR(m.probability(0.25), 0.25, 1e-12);
  m.observe(0.8, true);   // theta <= 0.8
  m.observe(0.2, false);  // theta > 0.2
  EXPECT_EQ(m.probability(0.1), 0.0);
  EXPECT_EQ(m.probability(0.9), 1.0);
  EXPECT_NEAR(m.probability(0.5), 0.5, 1e-12);
}

TEST(ThresholdModel, BelowIsTheMirror) {
  ThresholdModel m(0, 1, ThresholdModel::Direction::Below);
  m.observe(0.2, true);   // theta >= 0.2
  m.observe(0.8, false);  // theta < 0.8
  EXPECT_EQ(m.probability(0.1), 1.0);
  EXPECT_EQ(m.probability(0.9), 0.0);
  EXPECT_NEAR(m.probability(0.5), 0.5, 1e-12);
}

TEST(ThresholdModel, ContradictionGivesOneHalf) {
  ThresholdModel m(0, 1, ThresholdModel::Direction::Above);
  m.observe(0.3, true);
  m.observe(0.6, false);
  EXPECT_EQ(m.probability(0.0), 0.5);
  EXPECT_EQ(m.probability(1.0), 0.5);
  EXPECT_EQ(bernoulliEntropyBits(m.probability(0.5)), 1.0);
}

TEST(TableModel, TriStateWithLatestLabel) {
  TableModel t;
  EXPECT_EQ(t.probability("table"), 0.5);
  t.observe("table", true);
  EXPECT_EQ(t.probability("table"), 1.0);
  t.observe("table", false);
  EXPECT_EQ(t.probability("table"), 0.0);
  EXPECT_EQ(t.probability("shelf"), 0.5);
}

TEST(Entropy, Bits) {
  EXPECT_EQ(bernoulliEntropyBits(0.0), 0.0);
  EXPECT_EQ(bernoulliEntropyBits(1.0), 0.0);
  EXPECT_NEAR(bernoulliEntropyBits(0.5), 1.0, 1e-15);
  EXPECT_NEAR(bernoulliEntropyBits(0.25), 0.8112781244591328, 1e-12);
  EXPECT_EQ(bernoulliEntropyBits(-0.2), 0.0);
  EXPECT_EQ(bernoulliEntropyBits(1.5), 0.0);
}

TEST(Factor, FromSpecBuildsEachKind) {
  cbtl::ir::ModelFactor spec;
  spec.label = "t";
  spec.kind = cbtl::ir::FactorKind::Interval;
  spec.lo = 0;
  spec.hi = 1;
  Factor f = Factor::fromSpec(spec);
  f.observe(0.5, true);
  EXPECT_EQ(f.probability(0.5), 1.0);
  spec.kind = cbtl::ir::FactorKind::Threshold;
  spec.direction = cbtl::ir::ThresholdDirection::Below;
  Factor g = Factor::fromSpec(spec);
  g.observe(0.5, false);
  EXPECT_EQ(g.probability(0.6), 0.0);
  spec.kind = cbtl::ir::FactorKind::Table;
  Factor h = Factor::fromSpec(spec);
  EXPECT_TRUE(h.isTable());
  h.observe("a", true);
  EXPECT_EQ(h.probability("a"), 1.0);
}

// describeFactor: what a model believes, in words, and "unknown (no data)" where it has nothing to go on.
TEST(ModelSummary, SaysWhatIsLearnedAndWhatIsOnlyThePrior) {
  cbtl::ir::ModelFactor interval;
  interval.label = "temp";
  interval.kind = cbtl::ir::FactorKind::Interval;
  interval.lo = 25;
  interval.hi = 35;
  Factor f = Factor::fromSpec(interval);
  EXPECT_EQ(describeFactor(f), "unknown (no data): the declared range 25 to 35");
  f.observe(27.0, false);
  EXPECT_EQ(describeFactor(f), "nothing liked yet, 1 refused; 1 answer");
  f.observe(30.0, true);
  f.observe(32.0, true);
  EXPECT_EQ(describeFactor(f),
            "liked from 30 to 32 (the lower bound between 27 and 30, the upper between 32 and 35); 3 answers");

  cbtl::ir::ModelFactor threshold;
  threshold.kind = cbtl::ir::FactorKind::Threshold;
  threshold.lo = 0;
  threshold.hi = 1;
  threshold.direction = cbtl::ir::ThresholdDirection::Below;
  Factor t = Factor::fromSpec(threshold);
  EXPECT_EQ(describeFactor(t), "unknown (no data): holds at or below a threshold somewhere in 0 to 1");
  t.observe(0.4, true);
  t.observe(0.8, false);
  EXPECT_EQ(describeFactor(t), "holds at or below a threshold between 0.4 and 0.8; 2 answers");

  cbtl::ir::ModelFactor table;
  table.kind = cbtl::ir::FactorKind::Table;
  Factor k = Factor::fromSpec(table);
  EXPECT_EQ(describeFactor(k), "unknown (no data)");
  k.observe(std::string("ranch"), true);
  k.observe(std::string("ketchup"), false);
  EXPECT_EQ(describeFactor(k), "liked: ranch; refused: ketchup; 2 answers");
}
