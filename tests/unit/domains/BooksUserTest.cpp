// The Books user's hidden taste (over books.cbtl's catalogue), range of motion and words.
#include "domains/books/BooksUser.h"

#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using cbtl::domains::books::BookCatalog;
using cbtl::domains::books::BooksUser;
using cbtl::domains::books::Interval;
namespace world = cbtl::world;

const BookCatalog& catalog() {
  static const BookCatalog c = BookCatalog::fromProgram(cbtl::test::programFacts("books"));
  return c;
}

TEST(BooksUser, PaperUserEnjoysCosmosAndPrideAndPrejudiceOnly) {
  const BooksUser u = BooksUser::paperDefault();
  ASSERT_EQ(catalog().size(), 9u);
  std::vector<std::string> enjoyed;
  for (const auto& b : catalog().books())
    if (u.enjoys(b).value()) enjoyed.push_back(b.entry);
  EXPECT_EQ(enjoyed, (std::vector<std::string>{"cosmos", "prideAndPrejudice"}));
  EXPECT_NE(u.taste().hiddenPreference().find("romances"), std::string::npos);
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
  const auto& cosmos = *catalog().byEntry("cosmos");
  const auto& mobyDick = *catalog().byEntry("mobyDick");
  EXPECT_EQ(BooksUser::reaction(cosmos, false, false), "I can't reach there.");
  EXPECT_EQ(BooksUser::reaction(cosmos, true, true), "Thank you, I love Cosmos!");
  EXPECT_EQ(BooksUser::reaction(mobyDick, true, false), "Thanks, but Moby Dick is not for me.");
}

TEST(BooksUser, ReactionsAreLabelledFeedbackOnTheProgramsItem) {
  const BooksUser u = BooksUser::paperDefault();
  const auto liked = u.react(*catalog().byEntry("prideAndPrejudice")).value();
  EXPECT_EQ(liked.item.name, "prideAndPrejudice");
  EXPECT_EQ(liked.liked, true);
  EXPECT_EQ(liked.text, "Thank you, I love Pride and Prejudice!");
  const auto disliked = u.react(*catalog().byEntry("mobyDick")).value();
  EXPECT_EQ(disliked.liked, false);
}

TEST(BooksUser, RejectsBadIntervals) {
  const auto taste = BooksUser::paperDefault().taste();
  EXPECT_THROW(BooksUser(taste, Interval{0.3, 0.1}), std::invalid_argument);
  EXPECT_THROW(BooksUser(taste, Interval{-0.1, 0.3}), std::invalid_argument);
}

}  // namespace
