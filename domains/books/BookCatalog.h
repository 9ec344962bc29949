// BookCatalog.h — the Book entries of the program (books.cbtl `items standardBooks : Book`), read from the
// program's item sets rather than written down again: entry name, title, scene body, and the item as the
// program's `model text` factor shows it to a text-preference model.
//
// The catalogue is the first item set of type Book, in declaration order. Each entry needs a text `title` and a
// text `body` (a movable body of the scene); every declared field becomes a descriptor by the conversion of
// rt::ItemDescriptors (runtime/core/ItemDescriptors.h), so the simulated user's descriptor rule and a
// language-model judge read exactly what the program's text factor reads.
#pragma once

#include "domains/ProgramFacts.h"
#include "runtime/textpref/Item.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::domains::books {

struct Book {
  std::string entry;  // item entry name in the program
  std::string title;
  std::string body;     // movable body in the scene
  textpref::Item item;  // name = entry; one descriptor per declared field
};

class BookCatalog {
 public:
  // Throws std::invalid_argument when the program has no item set of type Book, or an entry lacks a text
  // title or body, or a field is not a literal.
  static BookCatalog fromProgram(const ProgramFacts& program);

  const std::vector<Book>& books() const { return books_; }
  std::size_t size() const { return books_.size(); }
  // The book with this scene body / entry name; null for anything else.
  const Book* byBody(std::string_view body) const;
  const Book* byEntry(std::string_view entry) const;

 private:
  explicit BookCatalog(std::vector<Book> books) : books_(std::move(books)) {}
  std::vector<Book> books_;
};

}  // namespace cbtl::domains::books
