// GraphJsonNode.h — the JSON access layer of the graph reader (GraphJsonReader.cpp, its only user): one object of
// the document with its JSON pointer, typed field access, and the failure every malformed part becomes (outcome,
// pointer, message). Kept apart from the reader so that each stays one concern: how a document is walked safely,
// and what a constraint graph's fields are.
#pragma once

#include "ir/GraphJsonReader.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::ir::graphjson {

using nlohmann::json;

// Thrown by the reader only; readGraphJson turns it into the result.
struct ReadFailure {
  GraphReadOutcome outcome;
  std::string pointer, message;
};

[[noreturn]] inline void fail(GraphReadOutcome outcome, const std::string& pointer, std::string message) {
  throw ReadFailure{outcome, pointer, std::move(message)};
}

// RFC 6901: '~' and '/' inside a key are escaped.
inline std::string child(const std::string& path, std::string_view key) {
  std::string out = path + "/";
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}
inline std::string child(const std::string& path, std::size_t index) { return fmt::format("{}/{}", path, index); }

inline const char* typeName(const json& j) {
  switch (j.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    default:
      return "a number";
  }
}

[[noreturn]] inline void wrongType(const json& j, const std::string& path, const char* wanted) {
  fail(GraphReadOutcome::WrongType, path, fmt::format("expected {}, found {}", wanted, typeName(j)));
}

// One object of the document with its pointer: typed access to its fields.
class Node {
 public:
  Node(const json& j, std::string path) : j_(j), path_(std::move(path)) {
    if (!j_.is_object()) wrongType(j_, path_, "an object");
  }
  const std::string& path() const { return path_; }
  std::string at(const char* key) const { return child(path_, key); }
  bool has(const char* key) const { return j_.contains(key); }
  std::size_t size() const { return j_.size(); }

  const json& field(const char* key) const {
    auto it = j_.find(key);
    if (it == j_.end()) fail(GraphReadOutcome::MissingField, at(key), "missing field");
    return *it;
  }
  Node object(const char* key) const { return Node(field(key), at(key)); }
  const json& array(const char* key) const {
    const json& a = field(key);
    if (!a.is_array()) wrongType(a, at(key), "an array");
    return a;
  }
  std::string text(const char* key) const {
    const json& s = field(key);
    if (!s.is_string()) wrongType(s, at(key), "a string");
    return s.get<std::string>();
  }
  std::string optText(const char* key) const { return has(key) ? text(key) : std::string(); }
  bool boolean(const char* key) const {
    const json& b = field(key);
    if (!b.is_boolean()) wrongType(b, at(key), "a boolean");
    return b.get<bool>();
  }
  double number(const char* key) const {
    const json& n = field(key);
    if (!n.is_number()) wrongType(n, at(key), "a number");
    return n.get<double>();
  }
  // An integer in [lo, hi]; a fraction or a value outside is a WrongType.
  std::int64_t integer(const char* key, std::int64_t lo, std::int64_t hi) const {
    return integerValue(field(key), at(key), lo, hi);
  }
  std::uint32_t u32(const char* key) const {
    return static_cast<std::uint32_t>(integer(key, 0, std::numeric_limits<std::uint32_t>::max()));
  }
  std::vector<std::string> texts(const char* key) const {
    std::vector<std::string> out;
    const json& a = array(key);
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_string()) wrongType(a[i], child(at(key), i), "a string");
      out.push_back(a[i].get<std::string>());
    }
    return out;
  }
  std::vector<std::string> optTexts(const char* key) const {
    return has(key) ? texts(key) : std::vector<std::string>{};
  }
  // Indices into a table of `count` elements (`what` names the table in messages).
  std::vector<std::uint32_t> indices(const char* key, std::size_t count, const char* what) const {
    std::vector<std::uint32_t> out;
    const json& a = array(key);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const std::string p = child(at(key), i);
      const auto v = integerValue(a[i], p, 0, std::numeric_limits<std::uint32_t>::max());
      if (static_cast<std::uint64_t>(v) >= count) {
        fail(GraphReadOutcome::OutOfRange, p, fmt::format("{} {} does not exist (the graph has {})", what, v, count));
      }
      out.push_back(static_cast<std::uint32_t>(v));
    }
    return out;
  }

  static std::int64_t integerValue(const json& n, const std::string& path, std::int64_t lo, std::int64_t hi) {
    if (n.is_number_integer()) {
      if (n.is_number_unsigned() && n.get<std::uint64_t>() > static_cast<std::uint64_t>(hi))
        fail(GraphReadOutcome::WrongType, path, fmt::format("{} is out of range [{}, {}]", n.dump(), lo, hi));
      const auto v = n.get<std::int64_t>();
      if (v < lo || v > hi)
        fail(GraphReadOutcome::WrongType, path, fmt::format("{} is out of range [{}, {}]", v, lo, hi));
      return v;
    }
    wrongType(n, path, "an integer");
  }

 private:
  const json& j_;
  std::string path_;
};

}  // namespace cbtl::ir::graphjson
