// ExampleItems.h — example data for the engine's own tests: a catalogue of nine example books with genre and
// topic descriptors and a user whose hidden rule picks two of them, and a context example (dips judged per
// meal). Test data only: a domain's items live in its .cbtl file and its users in its domain folder (the Books
// domain's catalogue is domains/books/books.cbtl, its user domains/books/BooksUser.h).
#pragma once

#include "runtime/textpref/Item.h"
#include "runtime/textpref/SimulatedUser.h"

#include <string>
#include <vector>

namespace cbtl::textpref::testing {

inline Item exampleBook(std::string title, std::string author, std::vector<std::string> genres,
                        std::vector<std::string> topics) {
  return Item{title,
              {{"title", {title}},
               {"author", {std::move(author)}},
               {"genre", std::move(genres)},
               {"topic", std::move(topics)}}};
}

inline std::vector<Item> exampleBooks() {
  return {
      exampleBook("Cosmos", "Carl Sagan", {"nonfiction", "science", "astronomy"},
                  {"universe", "cosmos", "history of science"}),
      exampleBook("Pride and Prejudice", "Jane Austen", {"fiction", "romance", "classic"},
                  {"marriage", "social class", "england"}),
      exampleBook("The Hitchhiker's Guide to the Galaxy", "Douglas Adams", {"fiction", "science fiction", "comedy"},
                  {"space travel", "galaxy", "absurdity"}),
      exampleBook("The Immortal Life of Henrietta Lacks", "Rebecca Skloot", {"nonfiction", "science", "biography"},
                  {"medicine", "medical ethics", "cell biology"}),
      exampleBook("The Diary of Anne Frank", "Anne Frank", {"nonfiction", "memoir", "history"},
                  {"world war ii", "holocaust", "adolescence"}),
      exampleBook("Into the Wild", "Jon Krakauer", {"nonfiction", "biography", "adventure"},
                  {"wilderness", "alaska", "self-reliance"}),
      exampleBook("Moby Dick", "Herman Melville", {"fiction", "adventure", "classic"}, {"whaling", "obsession", "sea"}),
      exampleBook("The Lord of the Rings", "J. R. R. Tolkien", {"fiction", "fantasy", "adventure"},
                  {"quest", "war", "friendship"}),
      exampleBook("And Then There Were None", "Agatha Christie", {"fiction", "mystery", "crime"},
                  {"murder", "island", "suspense"}),
  };
}

// Enjoys fictional romances and nonfiction about the universe: of exampleBooks(), Cosmos and Pride and Prejudice.
inline SimulatedUser exampleReader() {
  return SimulatedUser("reader",
                       "I only enjoy two kinds of books: fiction that is a romance, and grand nonfiction reflections "
                       "on the universe. I dislike every other book.",
                       DescriptorRule{{{"genre=fiction", "genre=romance"}, {"genre=nonfiction", "topic=universe"}}});
}

// Context example: dips judged per meal; the contexts are {"food", "food-type", "company"}.
inline std::vector<Item> exampleDips() {
  return {
      Item{"ketchup", {{"flavour", {"tangy", "sweet", "tomato"}}, {"texture", {"smooth"}}}},
      Item{"bbq sauce", {{"flavour", {"smoky", "sweet"}}, {"texture", {"thick"}}}},
      Item{"ranch dressing", {{"flavour", {"creamy", "herby"}}, {"texture", {"creamy"}}}},
      Item{"hummus", {{"flavour", {"savory", "chickpea"}}, {"texture", {"creamy"}}}},
      Item{"no dip", {{"flavour", {"plain"}}}},
  };
}

// Fries, raw vegetables, wedges, carrot sticks, tater tots.
inline std::vector<Context> exampleMeals() {
  auto meal = [](std::string food, std::vector<std::string> kinds, std::string company) {
    return Context{{{"food", {std::move(food)}}, {"food-type", std::move(kinds)}, {"company", {std::move(company)}}}};
  };
  return {
      meal("french fries", {"fried", "potato"}, "alone"),
      meal("raw vegetables", {"raw", "vegetable"}, "with friend"),
      meal("potato wedges", {"fried", "potato"}, "with tv"),
      meal("carrot sticks", {"raw", "vegetable"}, "alone"),
      meal("tater tots", {"fried", "potato"}, "with friend and tv"),
  };
}

// Wants a smoky sauce with fried food and a creamy dip with raw food.
inline SimulatedUser exampleDipUser() {
  return SimulatedUser(
      "dip",
      "With fried potatoes I want a smoky sauce such as BBQ; with raw vegetables I want a creamy dip such as "
      "ranch or hummus. I never want a dip I did not ask for.",
      DescriptorRule{{{"context.food-type=fried", "flavour=smoky"}, {"context.food-type=raw", "texture=creamy"}}});
}

}  // namespace cbtl::textpref::testing
