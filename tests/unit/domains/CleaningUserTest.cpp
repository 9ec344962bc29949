// The Cleaning user's hidden preference.
#include "domains/cleaning/CleaningUser.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using cbtl::domains::cleaning::CleaningUser;

TEST(CleaningUser, PaperUserWelcomesTheMiddleShelfAndTheFirstSideTableOnly) {
  const CleaningUser u = CleaningUser::paperDefault();
  EXPECT_TRUE(u.welcomes("shelfMiddle"));
  EXPECT_TRUE(u.welcomes("sideTable0"));
  for (const char* s : {"mainTable", "shelfBottom", "shelfTop", "sideTable1", "sideTable2", "bed"})
    EXPECT_FALSE(u.welcomes(s)) << s;
}

TEST(CleaningUser, RejectsNamesThatAreNotSurfaces) {
  EXPECT_THROW(CleaningUser({"kitchen"}), std::invalid_argument);
  EXPECT_NO_THROW(CleaningUser({"mainTable"}));
}

}  // namespace
