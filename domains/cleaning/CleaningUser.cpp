#include "domains/cleaning/CleaningUser.h"

#include "domains/home/HomeSurfaces.h"

#include <stdexcept>

namespace cbtl::domains::cleaning {

CleaningUser::CleaningUser(std::set<std::string, std::less<>> welcomeSurfaces) : welcome_(std::move(welcomeSurfaces)) {
  for (const std::string& s : welcome_) {
    if (!home::surfaceGeomOfMember(s)) throw std::invalid_argument("cleaning: '" + s + "' is not a Surface");
  }
}

CleaningUser CleaningUser::paperDefault() { return CleaningUser({"shelfMiddle", "sideTable0"}); }

}  // namespace cbtl::domains::cleaning
