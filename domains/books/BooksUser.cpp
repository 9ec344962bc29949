#include "domains/books/BooksUser.h"

#include "domains/books/BookCatalog.h"

#include <cmath>
#include <stdexcept>

namespace cbtl::domains::books {

BooksUser::BooksUser(std::set<std::string, std::less<>> enjoyedBooks, Interval reach)
    : enjoyed_(std::move(enjoyedBooks)), reach_(reach) {
  for (const std::string& e : enjoyed_)
    if (!bookOfEntry(e)) throw std::invalid_argument("books: '" + e + "' is not a Book entry");
  if (!std::isfinite(reach_.lo) || !std::isfinite(reach_.hi) || reach_.lo < 0 || reach_.lo > reach_.hi) {
    throw std::invalid_argument("books: the reach interval must satisfy 0 <= lo <= hi");
  }
}

BooksUser BooksUser::paperDefault() { return BooksUser({"cosmos", "prideAndPrejudice"}, Interval{0.1, 0.3}); }

Eigen::Vector3d BooksUser::romCentre(const world::Pose3& hand) {
  return hand.transformPoint(Eigen::Vector3d(0, 0, kRomHandOffset));
}

bool BooksUser::reaches(const world::Pose3& hand, const Eigen::Vector3d& point) const {
  return reach_.contains((point - romCentre(hand)).norm());
}

std::string BooksUser::reaction(std::string_view entry, bool reached) const {
  if (!reached) return "I can't reach there.";
  const auto book = bookOfEntry(entry);
  const std::string title = book ? std::string(kBooks[*book].title) : std::string(entry);
  return enjoys(entry) ? "Thank you, I love " + title + "!" : "Thanks, but " + title + " is not for me.";
}

}  // namespace cbtl::domains::books
