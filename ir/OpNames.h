// OpNames.h — the one table of names of the constraint graph's discriminators (ir/ConstraintGraph.h): the
// spelling `cbtlc emit` prints (text and JSON) and a graph reader parses.
//
// For every enum E: `name(E)` is total (every enumerator has exactly one name; ThresholdDirection::None's is
// the empty string, as the JSON dump writes a factor without a direction), and `<e>FromName` is its inverse:
// it returns the enumerator whose name is exactly `text` (case-sensitive, no trimming) and nullopt for any
// other string. `xFromName(name(x)) == x` for every enumerator x. A value that is no enumerator (a cast) is
// named "?", which no fromName accepts.
//
// Expression operators are named as written in the source ("+", "<=", "and", "=>"); every other node by a
// lower-case word ("num", "var", "enumset", "forall"). Type kinds are named as the type is spelled ("real",
// "SE2", "Conf").
#pragma once

#include "ir/ConstraintGraph.h"

#include <optional>
#include <string_view>

namespace cbtl::ir {

std::string_view name(Op op);
std::optional<Op> opFromName(std::string_view text);

std::string_view name(TypeKind kind);
std::optional<TypeKind> typeKindFromName(std::string_view text);

std::string_view name(PatternKind kind);  // glob | regex
std::optional<PatternKind> patternKindFromName(std::string_view text);

std::string_view name(FactorKind kind);  // interval | threshold | table | text
std::optional<FactorKind> factorKindFromName(std::string_view text);

std::string_view name(ThresholdDirection direction);  // "" | above | below
std::optional<ThresholdDirection> thresholdDirectionFromName(std::string_view text);

std::string_view name(TextScale scale);  // absolute | relative
std::optional<TextScale> textScaleFromName(std::string_view text);

std::string_view name(TextRating rating);  // digits | options
std::optional<TextRating> textRatingFromName(std::string_view text);

std::string_view name(ActionKind kind);  // call | for | if | block | allow
std::optional<ActionKind> actionKindFromName(std::string_view text);

std::string_view name(AllowPart part);  // robot | gripper | held
std::optional<AllowPart> allowPartFromName(std::string_view text);

std::string_view name(FunctionKind kind);  // function | sampler | action | feedback
std::optional<FunctionKind> functionKindFromName(std::string_view text);

// The binary operators (Add .. Iff), for printers that write them infix.
bool isBinary(Op op);

}  // namespace cbtl::ir
