#include "domains/books/BookCatalog.h"

#include "runtime/core/ItemDescriptors.h"

#include <stdexcept>

namespace cbtl::domains::books {

namespace {

std::string singleText(const Book& book, const char* field) {
  const auto it = book.item.descriptors.find(field);
  if (it == book.item.descriptors.end() || it->second.size() != 1) {
    throw std::invalid_argument("books: Book entry '" + book.entry + "' has no text field '" + field + "'");
  }
  return it->second.front();
}

}  // namespace

BookCatalog BookCatalog::fromProgram(const ProgramFacts& program) {
  const ir::ItemSet* set = firstItemSetOfType(program, "Book");
  if (set == nullptr) throw std::invalid_argument("books: the program declares no item set of type Book");
  std::vector<Book> books;
  for (const ir::ItemEntry& entry : set->entries) {
    Book book;
    book.entry = entry.name;
    book.item.name = entry.name;
    for (const auto& [field, value] : entry.fields) {
      const std::string& name = field;
      auto strings = rt::ItemDescriptors::fieldStrings(value, [&](const ir::Expr&) -> std::vector<std::string> {
        throw std::invalid_argument("books: field '" + name + "' of Book entry '" + entry.name + "' is not a literal");
      });
      if (!strings.empty()) book.item.descriptors[field] = std::move(strings);
    }
    book.title = singleText(book, "title");
    book.body = singleText(book, "body");
    books.push_back(std::move(book));
  }
  return BookCatalog(std::move(books));
}

const Book* BookCatalog::byBody(std::string_view body) const {
  for (const Book& b : books_)
    if (b.body == body) return &b;
  return nullptr;
}

const Book* BookCatalog::byEntry(std::string_view entry) const {
  for (const Book& b : books_)
    if (b.entry == entry) return &b;
  return nullptr;
}

}  // namespace cbtl::domains::books
