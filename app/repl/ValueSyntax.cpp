#include "app/repl/ValueSyntax.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace cbtl::app::repl {

namespace {

// A cursor over the typed text; every error names the column it stopped at.
class Reader {
 public:
  Reader(std::string_view text, SyntaxError& error) : text_(text), error_(error) {}

  void skipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool atEnd() {
    skipSpace();
    return pos_ >= text_.size();
  }
  std::size_t column() const { return pos_; }
  bool accept(char c) {
    skipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool expect(char c, const char* what) {
    if (accept(c)) return true;
    return fail(fmt::format("expected {}{}", what, atEnd() ? " before the end of the input" : ""));
  }
  bool fail(std::string message) {
    error_ = SyntaxError{pos_, std::move(message)};
    return false;
  }

  std::optional<std::string> identifier() {
    skipSpace();
    const std::size_t start = pos_;
    if (pos_ >= text_.size() || !(std::isalpha(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) {
      fail("expected a name");
      return std::nullopt;
    }
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    return std::string(text_.substr(start, pos_ - start));
  }

  std::optional<double> number() {
    skipSpace();
    const std::size_t start = pos_;
    if (pos_ < text_.size() && (text_[pos_] == '-' || text_[pos_] == '+')) ++pos_;
    while (pos_ < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.' || text_[pos_] == 'e' ||
            text_[pos_] == 'E' ||
            ((text_[pos_] == '-' || text_[pos_] == '+') && (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E'))))
      ++pos_;
    const std::string spelled(text_.substr(start, pos_ - start));
    double v = 0;
    const char* first = spelled.c_str() + (spelled.size() > 0 && spelled[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(first, spelled.c_str() + spelled.size(), v);
    if (spelled.empty() || ec != std::errc() || end != spelled.c_str() + spelled.size() || !std::isfinite(v)) {
      pos_ = start;
      fail(fmt::format("'{}' is not a number", spelled));
      return std::nullopt;
    }
    return v;
  }

  std::optional<sim::Value> literal() {
    skipSpace();
    if (pos_ >= text_.size()) {
      fail("expected a value");
      return std::nullopt;
    }
    const char c = text_[pos_];
    if (c == '"') return quoted();
    if (c == '(') return tuple();
    if (c == '{') return set();
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
      auto v = number();
      if (!v) return std::nullopt;
      return sim::Value::num(*v);
    }
    auto name = qualifiedName();
    if (!name) return std::nullopt;
    if (*name == "true" || *name == "false") return sim::Value::num(*name == "true" ? 1 : 0);
    return sim::Value::name(*name);
  }

 private:
  std::optional<std::string> qualifiedName() {
    auto name = identifier();
    while (name && pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      auto part = identifier();
      if (!part) return std::nullopt;
      *name += "." + *part;
    }
    return name;
  }

  std::optional<sim::Value> quoted() {
    ++pos_;  // the opening quote
    std::string s;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) ++pos_;
      s += text_[pos_++];
    }
    if (pos_ >= text_.size()) {
      fail("unterminated text: expected '\"'");
      return std::nullopt;
    }
    ++pos_;
    return sim::Value::name(std::move(s));
  }

  std::optional<sim::Value> tuple() {
    ++pos_;
    std::vector<double> v;
    if (!accept(')')) {
      do {
        auto x = number();
        if (!x) return std::nullopt;
        v.push_back(*x);
      } while (accept(','));
      if (!expect(')', "',' or ')'")) return std::nullopt;
    }
    return sim::Value::vec(std::move(v));
  }

  std::optional<sim::Value> set() {
    ++pos_;
    std::vector<std::string> members;
    if (!accept('}')) {
      do {
        auto m = qualifiedName();
        if (!m) return std::nullopt;
        members.push_back(*m);
      } while (accept(','));
      if (!expect('}', "',' or '}'")) return std::nullopt;
    }
    return sim::Value::names(std::move(members));
  }

  std::string_view text_;
  SyntaxError& error_;
  std::size_t pos_ = 0;
};

// The members a name of `type` may be, in declaration order (empty for a type without members).
std::vector<std::string> membersOf(const rt::Program& program, const rt::ValueType& type) {
  std::vector<std::string> names;
  if (type.kind == rt::ValueKind::Enum) {
    if (const ir::Enum* e = program.findEnum(type.typeName)) names = e->members;
  } else if (type.kind == rt::ValueKind::Item) {
    if (const ir::ItemSet* s = program.findItemSetOfType(type.typeName))
      for (const auto& entry : s->entries) names.push_back(entry.name);
  }
  return names;
}

// A member spelled bare or qualified (dips.ranch, Dip.ranch): its bare name when it is one of `type`'s.
std::optional<std::string> memberNamed(const rt::Program& program, const rt::ValueType& type, const std::string& name) {
  if (program.memberIndex(type.typeName, name)) return name;
  const auto dot = name.rfind('.');
  if (dot != std::string::npos && program.memberIndex(type.typeName, name.substr(dot + 1))) return name.substr(dot + 1);
  return std::nullopt;
}

std::string listed(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

std::optional<sim::Value> parseLiteral(std::string_view text, SyntaxError& error) {
  Reader r(text, error);
  auto v = r.literal();
  if (v && !r.atEnd()) {
    r.fail("unexpected text after the value");
    return std::nullopt;
  }
  return v;
}

std::optional<ParsedEvent> parseEvent(std::string_view text, SyntaxError& error) {
  Reader r(text, error);
  ParsedEvent event;
  auto name = r.identifier();
  if (!name) return std::nullopt;
  event.name = *name;
  if (!r.expect('(', "'(' after the event's name")) return std::nullopt;
  if (!r.accept(')')) {
    do {
      r.skipSpace();
      event.argColumns.push_back(r.column());
      auto v = r.literal();
      if (!v) return std::nullopt;
      event.args.push_back(std::move(*v));
    } while (r.accept(','));
    if (!r.expect(')', "',' or ')'")) return std::nullopt;
  }
  if (!r.atEnd()) {
    r.fail("unexpected text after the event");
    return std::nullopt;
  }
  return event;
}

bool coerceTo(const rt::Program& program, const rt::ValueType& type, sim::Value& value, std::string& error) {
  using K = rt::ValueKind;
  const std::string expected = describeType(program, type);
  auto mismatch = [&] {
    error = fmt::format("expected {}", expected);
    return false;
  };
  switch (type.kind) {
    case K::Real:
      return value.kind == sim::Value::Kind::Number || mismatch();
    case K::Int:
      if (value.kind != sim::Value::Kind::Number) return mismatch();
      if (value.number != std::round(value.number)) {
        error = fmt::format("expected an int, not {}", value.number);
        return false;
      }
      return true;
    case K::Bool:
      if (value.kind != sim::Value::Kind::Number || (value.number != 0 && value.number != 1)) return mismatch();
      return true;
    case K::Text:
      if (value.kind != sim::Value::Kind::Name) return mismatch();
      return true;
    case K::Enum:
    case K::Item: {
      if (value.kind != sim::Value::Kind::Name) return mismatch();
      const auto member = memberNamed(program, type, value.text);
      if (!member) {
        error = fmt::format("'{}' is not a {} ({})", value.text, type.typeName, listed(membersOf(program, type)));
        return false;
      }
      value.text = *member;
      return true;
    }
    case K::Vec:
    case K::SE2:
    case K::SE3:
    case K::Conf:
      if (value.kind != sim::Value::Kind::Vector) return mismatch();
      if (value.vector.size() != type.width) {
        error = fmt::format("expected {} numbers for {}, not {}", type.width, expected, value.vector.size());
        return false;
      }
      return true;
    case K::Set: {
      if (value.kind != sim::Value::Kind::Names) return mismatch();
      const rt::ValueType element = program.setElementType(type);
      for (auto& m : value.members) {
        const auto member = memberNamed(program, element, m);
        if (!member) {
          error = fmt::format("'{}' is not a {} ({})", m, element.typeName, listed(membersOf(program, element)));
          return false;
        }
        m = *member;
      }
      return true;
    }
    case K::Range:
    case K::Void:
      break;
  }
  error = fmt::format("values of type {} cannot be typed in", expected);
  return false;
}

std::string describeType(const rt::Program& program, const rt::ValueType& type) {
  using K = rt::ValueKind;
  switch (type.kind) {
    case K::Real:
      return "a real number";
    case K::Int:
      return "an int";
    case K::Bool:
      return "true or false";
    case K::Text:
      return "a text (a name or \"quoted\")";
    case K::Enum:
    case K::Item:
      return fmt::format("a {} ({})", type.typeName, listed(membersOf(program, type)));
    case K::Vec:
      return fmt::format("a vec<{}> ({} numbers in parentheses)", type.width, type.width);
    case K::SE2:
      return "an SE2 pose (x, y, yaw)";
    case K::SE3:
      return "an SE3 pose (x, y, z, qx, qy, qz, qw)";
    case K::Conf:
      return fmt::format("a configuration ({} joint angles, rad)", type.width);
    case K::Set: {
      const rt::ValueType element = program.setElementType(type);
      return fmt::format("a set of {} ({{a, b}} of {})", element.typeName, listed(membersOf(program, element)));
    }
    case K::Range:
    case K::Void:
      break;
  }
  return rt::toString(type.kind);
}

std::optional<sim::FeedbackEvent> checkedEvent(const rt::Program& program, const std::string& text,
                                               std::string& error) {
  const auto caret = [&](std::size_t column) { return fmt::format("\n  {}\n  {}^", text, std::string(column, ' ')); };
  SyntaxError syntax;
  auto event = parseEvent(text, syntax);
  if (!event) {
    error = syntax.message + caret(syntax.column);
    return std::nullopt;
  }
  const auto& decls = program.graph().feedback;
  const auto decl =
      std::find_if(decls.begin(), decls.end(), [&](const ir::Function& f) { return f.name == event->name; });
  if (decl == decls.end()) {
    error = fmt::format("no feedback event named '{}' (list events)", event->name);
    return std::nullopt;
  }
  if (decl->params.size() != event->args.size()) {
    error = fmt::format("{} takes {} argument{}, not {}", decl->name, decl->params.size(),
                        decl->params.size() == 1 ? "" : "s", event->args.size());
    return std::nullopt;
  }
  for (std::size_t i = 0; i < event->args.size(); ++i) {
    std::string why;
    if (!coerceTo(program, program.typeOf(decl->params[i].type), event->args[i], why)) {
      error = fmt::format("{}, argument {} ({}): {}", decl->name, i + 1, decl->params[i].name, why) +
              caret(event->argColumns[i]);
      return std::nullopt;
    }
  }
  return sim::FeedbackEvent{event->name, std::move(event->args)};
}

}  // namespace cbtl::app::repl
