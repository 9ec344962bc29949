// ValueSyntax.h — the values a person types in the REPL (observations, feedback events, "why not" values) and how
// they become the simulator boundary's values (runtime/sim/DomainSimulator.h), checked against a declared type.
//
//   literal   := number | 'true' | 'false' | name | "text" | '(' number {',' number} ')' | '{' [name {',' name}] '}'
//   name      := identifier {'.' identifier}          (an enum member or item entry, optionally qualified: dips.ranch)
//   event     := identifier '(' [literal {',' literal}] ')'
//
// Errors carry the 0-based column in the parsed text, so the REPL can point a caret at it.
#pragma once

#include "runtime/core/Program.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::app::repl {

struct SyntaxError {
  std::size_t column = 0;
  std::string message;
};

// One literal, the whole of `text` (surrounding white space allowed); the value's kind follows its spelling
// (a name or "text" is Name, a number or true/false is Number, a tuple is Vector, a set is Names).
std::optional<sim::Value> parseLiteral(std::string_view text, SyntaxError& error);

struct ParsedEvent {
  std::string name;
  std::vector<sim::Value> args;
  std::vector<std::size_t> argColumns;  // where each argument starts in the text
};
std::optional<ParsedEvent> parseEvent(std::string_view text, SyntaxError& error);

// A feedback event as typed, checked against its `feedback` declaration: its name, its argument count and every
// argument's type. On error, nullopt and a message of three lines: what is wrong, the text, a caret under it.
std::optional<sim::FeedbackEvent> checkedEvent(const rt::Program& program, const std::string& text, std::string& error);

// Makes `value` the form the boundary uses for `type` (true/false for a bool, a qualified member's last part, a
// text that was spelled as a name) and checks that it fits: a member of the enum or item set, an integer for int,
// the width of a vector. Returns false with a message naming what was expected.
bool coerceTo(const rt::Program& program, const rt::ValueType& type, sim::Value& value, std::string& error);

// How a type reads to a person: "real", "Dip (ketchup, bbq, ranch, hummus, noDip)", "SE2 (x, y, yaw)".
std::string describeType(const rt::Program& program, const rt::ValueType& type);

}  // namespace cbtl::app::repl
