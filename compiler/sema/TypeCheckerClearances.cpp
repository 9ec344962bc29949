// check-types: clearances. A clearance's distance, and an `allow` statement's part, mode, target and distance.
// Distances carry a unit (m, cm or mm) and are never negative: the part of the language that keeps people safe
// should not depend on a reader guessing whether 5 means metres or centimetres. Whether the named bodies exist is
// checked against the world file by the check-world pass.
#include "compiler/sema/TypeCheckerInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::detail {
namespace {

// Other units of length, and what a distance in one is in a unit the language takes.
struct Conversion {
  double factor;
  const char* unit;
};
std::optional<Conversion> conversionFor(const std::string& word) {
  static const std::map<std::string, Conversion> units = {
      {"km", {1000, "m"}},      {"dm", {10, "cm"}},    {"in", {2.54, "cm"}},    {"inch", {2.54, "cm"}},
      {"inches", {2.54, "cm"}}, {"ft", {30.48, "cm"}}, {"foot", {30.48, "cm"}}, {"feet", {30.48, "cm"}},
  };
  if (auto it = units.find(word); it != units.end()) return it->second;
  return std::nullopt;
}

// Units spelled out in full, mapped to the unit the language takes; a did-you-mean for each.
std::string unitFor(const std::string& word) {
  static const std::map<std::string, std::string> spelled = {
      {"metre", "m"},       {"metres", "m"},       {"meter", "m"},       {"meters", "m"},
      {"centimetre", "cm"}, {"centimetres", "cm"}, {"centimeter", "cm"}, {"centimeters", "cm"},
      {"millimetre", "mm"}, {"millimetres", "mm"}, {"millimeter", "mm"}, {"millimeters", "mm"},
  };
  if (auto it = spelled.find(word); it != spelled.end()) return it->second;
  // Only longer words are compared by spelling: two-letter units are a letter apart from each other (km, cm).
  if (word.size() < 3) return "";
  return closestMatch(word, {"m", "cm", "mm"});
}

}  // namespace

void TypeChecker::checkLength(const Length& l, bool touchDepth) {
  if (!l.range.valid() || l.spelling.empty()) return;  // error recovery left no number (already reported)
  if (l.unit.name.empty()) {
    diags_.error("E0601", l.range, "a distance needs a unit: m, cm or mm")
        .help(fmt::format("write the unit after the number, e.g. '{} cm'", l.spelling));
    return;
  }
  if (l.unit.name != "m" && l.unit.name != "cm" && l.unit.name != "mm") {
    Diagnostic& d = diags_.error("E0601", l.unit.range,
                                 fmt::format("unknown unit '{}': a distance is in m, cm or mm", l.unit.name));
    const std::string guess = unitFor(l.unit.name);
    if (!guess.empty()) {
      d.help(fmt::format("did you mean '{}'?", guess));
    } else if (const auto c = conversionFor(l.unit.name)) {
      d.help(fmt::format("write '{} {}'", std::fabs(l.value) * c->factor, c->unit));
    }
    return;
  }
  if (l.negative) {
    Diagnostic& d = diags_.error("E0602", l.range, "a distance cannot be negative")
                        .help(fmt::format("write '{} {}'", l.spelling, l.unit.name));
    if (touchDepth) d.note("'touch' takes the depth the part may sink in, as a positive distance");
  }
}

void TypeChecker::checkClearance(ClearanceDecl& c) { checkLength(c.distance, false); }

void TypeChecker::checkAllow(ActionStmt& s) {
  AllowClause& a = *s.allow;
  if (!a.part.name.empty() && a.part.name != "robot" && a.part.name != "gripper" && a.part.name != "held") {
    Diagnostic& d = diags_.error("E0604", a.part.range,
                                 fmt::format("expected 'robot', 'gripper' or 'held', found '{}'", a.part.name));
    const std::string guess = closestMatch(a.part.name, {"robot", "gripper", "held"});
    if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
    d.note("an allow names the part it is for: any robot body, the gripper, or the object the robot holds");
  }
  if (!a.mode.name.empty() && a.mode.name != "near" && a.mode.name != "touch") {
    Diagnostic& d =
        diags_.error("E0604", a.mode.range, fmt::format("expected 'near' or 'touch', found '{}'", a.mode.name));
    const std::string guess = closestMatch(a.mode.name, {"near", "touch"});
    if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
    d.note("'near' lets the part come as close as the distance; 'touch' lets it touch and sink in that deep");
  }
  if (a.clearance == nullptr) {
    const Type* t = check(a.target.get());
    if (!t->isError() && t->kind != TypeKind::Text) {
      diags_
          .error("E0605", a.target->range,
                 fmt::format("the target of an allow must be a clearance or a text naming a scene body or geom, but "
                             "this is {}",
                             t->spelling))
          .help("name a declared clearance, or give the scene name as text, e.g. \"user_forearm_r\"");
    }
  }
  checkLength(a.length, a.mode.name == "touch");
  if (s.body.empty()) {
    diags_.error("E0604", s.range, "this allow has no action: it allows nothing")
        .help("put the actions that need the exception inside its braces, or remove it");
  }
}

}  // namespace cbtl::detail
