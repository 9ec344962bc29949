// BookCatalog.h — the nine books of books.cbtl (`items standardBooks : Book`): item entry, scene body and
// title, in declaration order (entry k is body "book_k").
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace cbtl::domains::books {

struct BookEntry {
  std::string_view entry;  // item entry name in books.cbtl
  std::string_view body;   // movable body in home.xml
  std::string_view title;
};

inline constexpr std::array<BookEntry, 9> kBooks{{
    {"cosmos", "book_0", "Cosmos"},
    {"prideAndPrejudice", "book_1", "Pride and Prejudice"},
    {"hitchhikersGuide", "book_2", "The Hitchhiker's Guide to the Galaxy"},
    {"henriettaLacks", "book_3", "The Immortal Life of Henrietta Lacks"},
    {"anneFrank", "book_4", "The Diary of Anne Frank"},
    {"intoTheWild", "book_5", "Into the Wild"},
    {"mobyDick", "book_6", "Moby Dick"},
    {"lordOfTheRings", "book_7", "The Lord of the Rings"},
    {"andThenThereWereNone", "book_8", "And Then There Were None"},
}};

// Index into kBooks of the book with this body / entry name; nullopt for anything else.
std::optional<std::size_t> bookOfBody(std::string_view body);
std::optional<std::size_t> bookOfEntry(std::string_view entry);

}  // namespace cbtl::domains::books
