#include "runtime/textpref/SimulatedUsers.h"

#include <algorithm>
#include <cctype>

namespace cbtl::textpref {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool fieldHas(const Descriptors& fields, const std::string& field, const std::string& value) {
  for (const auto& [key, values] : fields) {
    if (lower(key) != field) continue;
    for (const auto& v : values)
      if (lower(v) == value) return true;
  }
  return false;
}

bool testHolds(const std::string& test, const Item& item, const Context& context) {
  const auto eq = test.find('=');
  if (eq == std::string::npos) return false;
  const std::string field = lower(test.substr(0, eq));
  const std::string value = lower(test.substr(eq + 1));
  if (field == "item") return lower(item.name) == value;
  if (field.rfind("context.", 0) == 0) return fieldHas(context.fields, field.substr(8), value);
  return fieldHas(item.descriptors, field, value);
}

Item book(std::string title, std::string author, std::vector<std::string> genres, std::vector<std::string> topics) {
  return Item{title,
              {{"title", {title}},
               {"author", {std::move(author)}},
               {"genre", std::move(genres)},
               {"topic", std::move(topics)}}};
}

}  // namespace

bool DescriptorRule::matches(const Item& item, const Context& context) const {
  for (const auto& all : anyOf) {
    if (all.empty()) continue;
    if (std::all_of(all.begin(), all.end(), [&](const std::string& t) { return testHolds(t, item, context); }))
      return true;
  }
  return false;
}

SimulatedUser::SimulatedUser(std::string name, std::string hiddenPreference, DescriptorRule rule)
    : name_(std::move(name)), hiddenPreference_(std::move(hiddenPreference)), rule_(std::move(rule)) {}

Result<bool> SimulatedUser::enjoys(const Item& item, const Context& context) const {
  if (!judge_) return rule_.matches(item, context);
  auto assessment = judge_->assessWithTheta(item, context, hiddenPreference_);
  if (!assessment) return assessment.error();
  return assessment.value().probability >= 0.5 - 1e-6;
}

Result<FeedbackRecord> SimulatedUser::react(const Item& item, const Context& context) const {
  auto liked = enjoys(item, context);
  if (!liked) return liked.error();
  FeedbackRecord record;
  record.item = item;
  record.context = context;
  record.liked = liked.value();
  record.text = liked.value() ? "Thank you, I really enjoyed that!" : "Thanks, but I did not enjoy that one.";
  return record;
}

std::vector<Item> standardBooks() {
  return {
      book("Cosmos", "Carl Sagan", {"nonfiction", "science", "astronomy"},
           {"universe", "cosmos", "history of science"}),
      book("Pride and Prejudice", "Jane Austen", {"fiction", "romance", "classic"},
           {"marriage", "social class", "england"}),
      book("The Hitchhiker's Guide to the Galaxy", "Douglas Adams", {"fiction", "science fiction", "comedy"},
           {"space travel", "galaxy", "absurdity"}),
      book("The Immortal Life of Henrietta Lacks", "Rebecca Skloot", {"nonfiction", "science", "biography"},
           {"medicine", "medical ethics", "cell biology"}),
      book("The Diary of Anne Frank", "Anne Frank", {"nonfiction", "memoir", "history"},
           {"world war ii", "holocaust", "adolescence"}),
      book("Into the Wild", "Jon Krakauer", {"nonfiction", "biography", "adventure"},
           {"wilderness", "alaska", "self-reliance"}),
      book("Moby Dick", "Herman Melville", {"fiction", "adventure", "classic"}, {"whaling", "obsession", "sea"}),
      book("The Lord of the Rings", "J. R. R. Tolkien", {"fiction", "fantasy", "adventure"},
           {"quest", "war", "friendship"}),
      book("And Then There Were None", "Agatha Christie", {"fiction", "mystery", "crime"},
           {"murder", "island", "suspense"}),
  };
}

SimulatedUser booksUser() {
  return SimulatedUser(
      "books",
      "I only enjoy two kinds of books: fiction that is a romance, and grand nonfiction reflections on the "
      "universe. I dislike every other book.",
      DescriptorRule{{{"genre=fiction", "genre=romance"}, {"genre=nonfiction", "topic=universe"}}});
}

std::vector<Item> feedingDips() {
  return {
      Item{"ketchup", {{"flavour", {"tangy", "sweet", "tomato"}}, {"texture", {"smooth"}}}},
      Item{"bbq sauce", {{"flavour", {"smoky", "sweet"}}, {"texture", {"thick"}}}},
      Item{"ranch dressing", {{"flavour", {"creamy", "herby"}}, {"texture", {"creamy"}}}},
      Item{"hummus", {{"flavour", {"savory", "chickpea"}}, {"texture", {"creamy"}}}},
      Item{"no dip", {{"flavour", {"plain"}}}},
  };
}

std::vector<Item> feedingReadySignals() {
  return {
      Item{"button", {{"trigger", {"touch"}}, {"effort", {"hands"}}}},
      Item{"auto-continue", {{"trigger", {"timer"}}, {"effort", {"none"}}}},
      Item{"mouth open", {{"trigger", {"gesture"}}, {"effort", {"face"}}}},
  };
}

std::vector<Item> feedingVerbosityLevels() {
  return {
      Item{"silent", {{"speech", {"none"}}}},
      Item{"verbal", {{"speech", {"spoken"}}}},
  };
}

std::vector<Context> feedingMeals() {
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

SimulatedUser feedingDipUser() {
  return SimulatedUser(
      "feeding-dip",
      "With fried potatoes I want a smoky sauce such as BBQ; with raw vegetables I want a creamy dip such as "
      "ranch or hummus. I never want a dip I did not ask for.",
      DescriptorRule{{{"context.food-type=fried", "flavour=smoky"}, {"context.food-type=raw", "texture=creamy"}}});
}

SimulatedUser feedingSignalUser() {
  return SimulatedUser("feeding-signal",
                       "I want to signal that I am ready by opening my mouth; buttons and timers annoy me.",
                       DescriptorRule{{{"trigger=gesture"}}});
}

SimulatedUser feedingVerbosityUser() {
  return SimulatedUser("feeding-verbosity", "I prefer the robot to stay silent while it feeds me.",
                       DescriptorRule{{{"speech=none"}}});
}

}  // namespace cbtl::textpref
