#include "domains/books/BooksUser.h"

#include <cmath>
#include <stdexcept>

namespace cbtl::domains::books {

BooksUser::BooksUser(textpref::SimulatedUser taste, Interval reach) : taste_(std::move(taste)), reach_(reach) {
  if (!std::isfinite(reach_.lo) || !std::isfinite(reach_.hi) || reach_.lo < 0 || reach_.lo > reach_.hi) {
    throw std::invalid_argument("books: the reach interval must satisfy 0 <= lo <= hi");
  }
}

BooksUser BooksUser::paperDefault() {
  return BooksUser(textpref::SimulatedUser("books",
                                           "I only like two kinds of books: fictional romances, and grand, "
                                           "nonfictional reflections on the universe.",
                                           textpref::DescriptorRule{{{"tags=fiction", "tags=romance"},
                                                                     {"tags=nonfiction", "tags=universe"}}}),
                   Interval{0.1, 0.3});
}

Eigen::Vector3d BooksUser::romCentre(const world::Pose3& hand) {
  return hand.transformPoint(Eigen::Vector3d(0, 0, kRomHandOffset));
}

bool BooksUser::reaches(const world::Pose3& hand, const Eigen::Vector3d& point) const {
  return reach_.contains((point - romCentre(hand)).norm());
}

std::string BooksUser::reaction(const Book& book, bool reached, bool enjoyed) {
  if (!reached) return "I can't reach there.";
  return enjoyed ? "Thank you, I love " + book.title + "!" : "Thanks, but " + book.title + " is not for me.";
}

textpref::Result<textpref::FeedbackRecord> BooksUser::react(const Book& book) const {
  auto liked = enjoys(book);
  if (!liked) return liked.error();
  textpref::FeedbackRecord record;
  record.item = book.item;
  record.liked = liked.value();
  record.text = reaction(book, true, liked.value());
  return record;
}

}  // namespace cbtl::domains::books
