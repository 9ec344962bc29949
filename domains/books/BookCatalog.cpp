#include "domains/books/BookCatalog.h"

namespace cbtl::domains::books {

std::optional<std::size_t> bookOfBody(std::string_view body) {
  for (std::size_t i = 0; i < kBooks.size(); ++i)
    if (kBooks[i].body == body) return i;
  return std::nullopt;
}

std::optional<std::size_t> bookOfEntry(std::string_view entry) {
  for (std::size_t i = 0; i < kBooks.size(); ++i)
    if (kBooks[i].entry == entry) return i;
  return std::nullopt;
}

}  // namespace cbtl::domains::books
