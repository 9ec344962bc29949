// Item.h — what a text-preference constraint is asked about, and what the user said about it.
//
// An Item is a value of a `.cbtl` item domain: a name (unique within its domain) plus descriptor fields, each a
// key with a list of strings (one per declared field of the item type). A Context carries the parts of the
// observation that matter to the constraint (a situation the same item may be liked in or not). A FeedbackRecord
// is one reaction of the user to one item, as free text, as a boolean, or both.
#pragma once

#include "runtime/textpref/Result.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::textpref {

using Descriptors = std::map<std::string, std::vector<std::string>>;

struct Item {
  std::string name;         // identity of the item within its domain (the .cbtl entry name)
  Descriptors descriptors;  // field -> values, e.g. {"colour": {"red"}, "tags": {"round", "small"}}

  bool operator==(const Item&) const = default;
};

struct Context {
  Descriptors fields;  // e.g. {"food": {"french fries"}, "company": {"alone"}}
  bool empty() const { return fields.empty(); }
  bool operator==(const Context&) const = default;
};

struct FeedbackRecord {
  Item item;
  Context context;
  std::string text;           // what the user said, may be empty
  std::optional<bool> liked;  // an explicit yes/no, when the feedback event carries one
  bool operator==(const FeedbackRecord&) const = default;
};

// The item written for a prompt: "Cosmos (author: Carl Sagan; tags: nonfiction, science)". Fields are listed
// in key order, values in their declared order; an item without descriptors is just its name.
std::string describeItem(const Item& item);

// The context written for a prompt: "food: french fries; company: alone", or "" when empty.
std::string describeContext(const Context& context);

// One feedback line for a LearningPrompt: "<item description> [context] -> <text or liked/disliked>".
std::string describeFeedback(const FeedbackRecord& record);

// JSON conversions. The from-JSON functions validate the shape and report InvalidState on mismatch.
nlohmann::json toJson(const Item& item);
nlohmann::json toJson(const Context& context);
nlohmann::json toJson(const FeedbackRecord& record);
Result<Item> itemFromJson(const nlohmann::json& j);
Result<Context> contextFromJson(const nlohmann::json& j);
Result<FeedbackRecord> feedbackFromJson(const nlohmann::json& j);

}  // namespace cbtl::textpref
