// BooksUser.h — the hidden Books user: which books they enjoy, their functional range of motion, and what
// they say at a handover.
//
// The paper's user (paperDefault): hidden text "I only like two kinds of books: fictional romances, and
// grand, nonfictional reflections on the universe"; among the nine standard books the reference's ground
// truth enjoys exactly Cosmos and Pride and Prejudice, so the simulated user enjoys
// those two entries. Range of motion: a handover at point p is reachable iff the distance from p to the
// sphere centre lies in [0.1, 0.3] m (bounds included; the reference's hidden interval);
// the centre is the hand frame moved romHandOffset along its z (books.cbtl romCentre).
// Utterances: unreachable "I can't reach there." (the paper's words); reached and enjoyed "Thank you, I love
// <title>!"; reached and not enjoyed "Thanks, but <title> is not for me." — the title is named so a text
// model can learn from the words, the hidden description itself is never said.
#pragma once

#include "robot/world/Pose.h"

#include <set>
#include <string>
#include <string_view>

namespace cbtl::domains::books {

inline constexpr double kRomHandOffset = 0.2;  // metres from the hand along its z to the sphere centre

struct Interval {
  double lo = 0, hi = 0;  // metres, closed
  bool contains(double v) const { return v >= lo && v <= hi; }
};

class BooksUser {
 public:
  // Throws std::invalid_argument for an unknown book entry or an interval outside 0 <= lo <= hi.
  BooksUser(std::set<std::string, std::less<>> enjoyedBooks, Interval reach);
  static BooksUser paperDefault();

  bool enjoys(std::string_view entry) const { return enjoyed_.count(entry) > 0; }
  const std::set<std::string, std::less<>>& enjoyedBooks() const { return enjoyed_; }
  const Interval& reach() const { return reach_; }

  // The centre of the reachable shell for a hand frame (world frame, metres).
  static Eigen::Vector3d romCentre(const world::Pose3& hand);
  // Whether a handover at `point` is reachable for a hand at `hand`.
  bool reaches(const world::Pose3& hand, const Eigen::Vector3d& point) const;
  // What the user says when handed the book `entry`.
  std::string reaction(std::string_view entry, bool reached) const;

 private:
  std::set<std::string, std::less<>> enjoyed_;
  Interval reach_;
};

}  // namespace cbtl::domains::books
