// CleaningUser.h — the hidden preference of the Cleaning user: the surfaces they let the robot clean.
//
// The paper's user (appendix, Cleaning: "only two surfaces should be cleaned by the robot") and the
// reference code's ground truth (the user lets the robot clean the middle shelf layer
// and the first side table) — paperDefault() — welcomes a wipe of shelfMiddle or sideTable0 ("Thanks for
// cleaning there") and admonishes one of any other surface ("Don't clean there"). Surfaces are the members
// of cleaning.cbtl's `enum Surface`. The robot never reads this set: it learns it from the reactions.
#pragma once

#include <set>
#include <string>
#include <string_view>

namespace cbtl::domains::cleaning {

class CleaningUser {
 public:
  // Throws std::invalid_argument for a name that is not a Surface member.
  explicit CleaningUser(std::set<std::string, std::less<>> welcomeSurfaces);
  static CleaningUser paperDefault();

  // Whether the user is glad that `surface` (a Surface member) was cleaned.
  bool welcomes(std::string_view surface) const { return welcome_.count(surface) > 0; }
  const std::set<std::string, std::less<>>& welcomeSurfaces() const { return welcome_; }

 private:
  std::set<std::string, std::less<>> welcome_;
};

}  // namespace cbtl::domains::cleaning
