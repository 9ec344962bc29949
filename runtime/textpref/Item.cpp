#include "runtime/textpref/Item.h"

#include <fmt/core.h>

namespace cbtl::textpref {
namespace {

std::string joinValues(const std::vector<std::string>& values) {
  std::string out;
  for (const auto& v : values) {
    if (!out.empty()) out += ", ";
    out += v;
  }
  return out;
}

std::string describeFields(const Descriptors& fields) {
  std::string out;
  for (const auto& [key, values] : fields) {
    if (!out.empty()) out += "; ";
    out += fmt::format("{}: {}", key, joinValues(values));
  }
  return out;
}

Error stateError(const std::string& what) { return Error{ErrorKind::InvalidState, what, "", 0, 0}; }

Result<Descriptors> descriptorsFromJson(const nlohmann::json& j, const char* where) {
  if (!j.is_object()) return stateError(fmt::format("{} must be an object of string lists", where));
  Descriptors out;
  for (const auto& [key, values] : j.items()) {
    if (!values.is_array()) return stateError(fmt::format("{}.{} must be a list of strings", where, key));
    std::vector<std::string> list;
    for (const auto& v : values) {
      if (!v.is_string()) return stateError(fmt::format("{}.{} must contain only strings", where, key));
      list.push_back(v.get<std::string>());
    }
    out.emplace(key, std::move(list));
  }
  return out;
}

}  // namespace

std::string describeItem(const Item& item) {
  if (item.descriptors.empty()) return item.name;
  return fmt::format("{} ({})", item.name, describeFields(item.descriptors));
}

std::string describeContext(const Context& context) { return describeFields(context.fields); }

std::string describeFeedback(const FeedbackRecord& record) {
  std::string out = describeItem(record.item);
  if (!record.context.empty()) out += fmt::format(" [{}]", describeContext(record.context));
  out += " -> ";
  if (!record.text.empty()) {
    out += fmt::format("\"{}\"", record.text);
  } else if (record.liked.has_value()) {
    out += *record.liked ? "the user liked it" : "the user did not like it";
  } else {
    out += "no reaction";
  }
  return out;
}

nlohmann::json toJson(const Item& item) {
  return nlohmann::json{{"name", item.name}, {"descriptors", item.descriptors}};
}

nlohmann::json toJson(const Context& context) { return nlohmann::json(context.fields); }

nlohmann::json toJson(const FeedbackRecord& record) {
  nlohmann::json j{{"item", toJson(record.item)}, {"context", toJson(record.context)}, {"text", record.text}};
  j["liked"] = record.liked.has_value() ? nlohmann::json(*record.liked) : nlohmann::json(nullptr);
  return j;
}

Result<Item> itemFromJson(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("name") || !j["name"].is_string())
    return stateError("an item must be an object with a string \"name\"");
  Item item;
  item.name = j["name"].get<std::string>();
  if (j.contains("descriptors")) {
    auto d = descriptorsFromJson(j["descriptors"], "item.descriptors");
    if (!d) return d.error();
    item.descriptors = std::move(d).value();
  }
  return item;
}

Result<Context> contextFromJson(const nlohmann::json& j) {
  if (j.is_null()) return Context{};
  auto d = descriptorsFromJson(j, "context");
  if (!d) return d.error();
  return Context{std::move(d).value()};
}

Result<FeedbackRecord> feedbackFromJson(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("item")) return stateError("a feedback record must be an object with \"item\"");
  FeedbackRecord record;
  auto item = itemFromJson(j["item"]);
  if (!item) return item.error();
  record.item = std::move(item).value();
  if (j.contains("context")) {
    auto context = contextFromJson(j["context"]);
    if (!context) return context.error();
    record.context = std::move(context).value();
  }
  if (j.contains("text")) {
    if (!j["text"].is_string()) return stateError("feedback \"text\" must be a string");
    record.text = j["text"].get<std::string>();
  }
  if (j.contains("liked") && !j["liked"].is_null()) {
    if (!j["liked"].is_boolean()) return stateError("feedback \"liked\" must be a boolean or null");
    record.liked = j["liked"].get<bool>();
  }
  return record;
}

}  // namespace cbtl::textpref
