// The Books user's hidden taste, range of motion and words.
#include "domains/books/BooksUser.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using cbtl::domains::books::BooksUser;
using cbtl::domains::books::Interval;
namespace world = cbtl::world;

TEST(BooksUser, PaperUserEnjoysCosmosAndPrideAndPrejudiceOnly) {
  const BooksUser u = BooksUser::paperDefault();
  EXPECT_TRUE(u.enjoys("cosmos"));
  EXPECT_TRUE(u.enjoys("prideAndPrejudice"));
  for (const char* b : {"hitchhikersGuide", "henriettaLacks", "anneFrank", "intoTheWild", "mobyDick", "lordOfTheRings",
                        "andThenThereWereNone"})
    EXPECT_FALSE(u.enjoys(b)) << b;
}

TEST(BooksUser, ReachIsAClosedShellAroundTheOffsetHand) {
  const BooksUser u = BooksUser::paperDefault();
  // A hand at (1, 0, 0) whose z points along world x: the centre is (1.2, 0, 0).
  const world::Pose3 hand{Eigen::Vector3d(1, 0, 0),
                          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX())};
  EXPECT_TRUE(BooksUser::romCentre(hand).isApprox(Eigen::Vector3d(1.2, 0, 0)));
  EXPECT_FALSE(u.reaches(hand, Eigen::Vector3d(1.2, 0, 0)));  // d = 0: too close
  EXPECT_FALSE(u.reaches(hand, Eigen::Vector3d(1.2, 0.05, 0)));
  EXPECT_TRUE(u.reaches(hand, Eigen::Vector3d(1.2, 0.1, 0)));  // lower bound included
  EXPECT_TRUE(u.reaches(hand, Eigen::Vector3d(1.2, 0, 0.2)));
  EXPECT_TRUE(u.reaches(hand, Eigen::Vector3d(0.9, 0, 0)));  // upper bound included
  EXPECT_FALSE(u.reaches(hand, Eigen::Vector3d(1.2, 0, -0.31)));
}

TEST(BooksUser, WordsSayWhetherTheyReachedAndLikedIt) {
  const BooksUser u = BooksUser::paperDefault();
  EXPECT_EQ(u.reaction("cosmos", false), "I can't reach there.");
  EXPECT_EQ(u.reaction("cosmos", true), "Thank you, I love Cosmos!");
  EXPECT_EQ(u.reaction("mobyDick", true), "Thanks, but Moby Dick is not for me.");
}

TEST(BooksUser, RejectsUnknownBooksAndBadIntervals) {
  EXPECT_THROW(BooksUser({"ulysses"}, Interval{0.1, 0.3}), std::invalid_argument);
  EXPECT_THROW(BooksUser({"cosmos"}, Interval{0.3, 0.1}), std::invalid_argument);
  EXPECT_THROW(BooksUser({"cosmos"}, Interval{-0.1, 0.3}), std::invalid_argument);
}

}  // namespace
