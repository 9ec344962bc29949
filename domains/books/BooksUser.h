// BooksUser.h — the hidden Books user: which books they enjoy, their functional range of motion, and what
// they say at a handover. The one Books user: the simulator's, and the one `cbtl llm books` learns.
//
// Taste: a textpref::SimulatedUser over the program's Book entries (BookCatalog): a hidden preference text (what
// a language-model judge reads as theta) and the same preference as a DescriptorRule over the entries'
// descriptors. Without a judge the rule is the ground truth. The paper's user (paperDefault): hidden text "I only
// like two kinds of books: fictional romances, and grand, nonfictional reflections on the universe", rule
// {tags=fiction, tags=romance} or {tags=nonfiction, tags=universe}; over books.cbtl's nine books it enjoys exactly
// Cosmos and Pride and Prejudice, the reference's ground truth.
// Range of motion: a handover at point p is reachable iff the distance from p to the sphere centre lies in
// [0.1, 0.3] m (bounds included; the reference's hidden interval); the centre is the hand frame moved
// romHandOffset along its z (books.cbtl romCentre).
// Utterances: unreachable "I can't reach there." (the paper's words); reached and enjoyed "Thank you, I love
// <title>!"; reached and not enjoyed "Thanks, but <title> is not for me." — the title is named so a text
// model can learn from the words, the hidden description itself is never said.
#pragma once

#include "domains/books/BookCatalog.h"
#include "robot/world/Pose.h"
#include "runtime/textpref/SimulatedUser.h"

#include <string>

namespace cbtl::domains::books {

inline constexpr double kRomHandOffset = 0.2;  // metres from the hand along its z to the sphere centre

struct Interval {
  double lo = 0, hi = 0;  // metres, closed
  bool contains(double v) const { return v >= lo && v <= hi; }
};

class BooksUser {
 public:
  // Throws std::invalid_argument for an interval outside 0 <= lo <= hi.
  BooksUser(textpref::SimulatedUser taste, Interval reach);
  static BooksUser paperDefault();

  // Ground truth: does the user enjoy `book`? Errors only with a language-model judge (taste()).
  textpref::Result<bool> enjoys(const Book& book) const { return taste_.enjoys(book.item); }
  // The hidden text and rule; a caller may attach a language-model judge here.
  textpref::SimulatedUser& taste() { return taste_; }
  const textpref::SimulatedUser& taste() const { return taste_; }
  const Interval& reach() const { return reach_; }

  // The centre of the reachable shell for a hand frame (world frame, metres).
  static Eigen::Vector3d romCentre(const world::Pose3& hand);
  // Whether a handover at `point` is reachable for a hand at `hand`.
  bool reaches(const world::Pose3& hand, const Eigen::Vector3d& point) const;
  // What the user says when handed `book`, given whether they reached it and whether they enjoy it.
  static std::string reaction(const Book& book, bool reached, bool enjoyed);
  // A reached handover as a feedback record: the book's item, liked = enjoys(book), text = reaction(...).
  textpref::Result<textpref::FeedbackRecord> react(const Book& book) const;

 private:
  textpref::SimulatedUser taste_;
  Interval reach_;
};

}  // namespace cbtl::domains::books
