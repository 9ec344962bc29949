#include "ir/OpNames.h"

#include <array>
#include <cstddef>
#include <utility>

namespace cbtl::ir {
namespace {

template <class E>
using Entry = std::pair<E, std::string_view>;

// Each table lists every enumerator once, in declaration order, so that an enumerator indexes its own entry;
// inDeclarationOrder() checks that at compile time against the enum's last enumerator.
template <class E, std::size_t N>
constexpr bool inDeclarationOrder(const std::array<Entry<E>, N>& table, E last) {
  for (std::size_t i = 0; i < N; ++i) {
    if (static_cast<std::size_t>(table[i].first) != i) return false;
  }
  return N == static_cast<std::size_t>(last) + 1;
}

template <class E, std::size_t N>
std::string_view lookUp(const std::array<Entry<E>, N>& table, E value) {
  const auto i = static_cast<std::size_t>(value);
  return i < N ? table[i].second : std::string_view("?");
}

template <class E, std::size_t N>
std::optional<E> find(const std::array<Entry<E>, N>& table, std::string_view text) {
  for (const auto& [value, spelling] : table) {
    if (spelling == text) return value;
  }
  return std::nullopt;
}

constexpr std::array<Entry<Op>, 42> kOps = {{
    {Op::Num, "num"},         {Op::Str, "str"},       {Op::Bool, "bool"},
    {Op::Var, "var"},         {Op::Obs, "obs"},       {Op::Const, "const"},
    {Op::Enum, "enum"},       {Op::Item, "item"},     {Op::EnumSet, "enumset"},
    {Op::ItemSet, "itemset"}, {Op::Param, "param"},   {Op::Local, "local"},
    {Op::Family, "family"},   {Op::Call, "call"},     {Op::Member, "member"},
    {Op::Index, "index"},     {Op::Neg, "neg"},       {Op::Not, "not"},
    {Op::Add, "+"},           {Op::Sub, "-"},         {Op::Mul, "*"},
    {Op::Div, "/"},           {Op::Mod, "%"},         {Op::Pow, "^"},
    {Op::Eq, "=="},           {Op::Ne, "!="},         {Op::Lt, "<"},
    {Op::Le, "<="},           {Op::Gt, ">"},          {Op::Ge, ">="},
    {Op::And, "and"},         {Op::Or, "or"},         {Op::Implies, "=>"},
    {Op::Iff, "<=>"},         {Op::Range, "range"},   {Op::In, "in"},
    {Op::Forall, "forall"},   {Op::Exists, "exists"}, {Op::If, "if"},
    {Op::Tuple, "tuple"},     {Op::List, "list"},     {Op::Invalid, "invalid"},
}};
static_assert(inDeclarationOrder(kOps, Op::Invalid));

constexpr std::array<Entry<TypeKind>, 15> kTypeKinds = {{
    {TypeKind::Error, "error"},
    {TypeKind::Real, "real"},
    {TypeKind::Int, "int"},
    {TypeKind::Bool, "bool"},
    {TypeKind::Text, "text"},
    {TypeKind::Enum, "enum"},
    {TypeKind::Item, "item"},
    {TypeKind::Vec, "vec"},
    {TypeKind::SE2, "SE2"},
    {TypeKind::SE3, "SE3"},
    {TypeKind::Conf, "Conf"},
    {TypeKind::Set, "set"},
    {TypeKind::Tuple, "tuple"},
    {TypeKind::Range, "range"},
    {TypeKind::Void, "void"},
}};
static_assert(inDeclarationOrder(kTypeKinds, TypeKind::Void));

constexpr std::array<Entry<PatternKind>, 2> kPatternKinds = {
    {{PatternKind::Glob, "glob"}, {PatternKind::Regex, "regex"}}};
static_assert(inDeclarationOrder(kPatternKinds, PatternKind::Regex));

constexpr std::array<Entry<FactorKind>, 4> kFactorKinds = {{{FactorKind::Interval, "interval"},
                                                            {FactorKind::Threshold, "threshold"},
                                                            {FactorKind::Table, "table"},
                                                            {FactorKind::Text, "text"}}};
static_assert(inDeclarationOrder(kFactorKinds, FactorKind::Text));

constexpr std::array<Entry<ThresholdDirection>, 3> kDirections = {
    {{ThresholdDirection::None, ""}, {ThresholdDirection::Above, "above"}, {ThresholdDirection::Below, "below"}}};
static_assert(inDeclarationOrder(kDirections, ThresholdDirection::Below));

constexpr std::array<Entry<TextScale>, 2> kScales = {
    {{TextScale::Absolute, "absolute"}, {TextScale::Relative, "relative"}}};
static_assert(inDeclarationOrder(kScales, TextScale::Relative));

constexpr std::array<Entry<TextRating>, 2> kRatings = {
    {{TextRating::Digits, "digits"}, {TextRating::Options, "options"}}};
static_assert(inDeclarationOrder(kRatings, TextRating::Options));

constexpr std::array<Entry<ActionKind>, 5> kActionKinds = {{{ActionKind::Call, "call"},
                                                            {ActionKind::For, "for"},
                                                            {ActionKind::If, "if"},
                                                            {ActionKind::Block, "block"},
                                                            {ActionKind::Allow, "allow"}}};
static_assert(inDeclarationOrder(kActionKinds, ActionKind::Allow));

constexpr std::array<Entry<AllowPart>, 3> kAllowParts = {
    {{AllowPart::Robot, "robot"}, {AllowPart::Gripper, "gripper"}, {AllowPart::Held, "held"}}};
static_assert(inDeclarationOrder(kAllowParts, AllowPart::Held));

constexpr std::array<Entry<FunctionKind>, 4> kFunctionKinds = {{{FunctionKind::Function, "function"},
                                                                {FunctionKind::Sampler, "sampler"},
                                                                {FunctionKind::Action, "action"},
                                                                {FunctionKind::Feedback, "feedback"}}};
static_assert(inDeclarationOrder(kFunctionKinds, FunctionKind::Feedback));

}  // namespace

std::string_view name(Op op) { return lookUp(kOps, op); }
std::optional<Op> opFromName(std::string_view text) { return find(kOps, text); }

std::string_view name(TypeKind kind) { return lookUp(kTypeKinds, kind); }
std::optional<TypeKind> typeKindFromName(std::string_view text) { return find(kTypeKinds, text); }

std::string_view name(PatternKind kind) { return lookUp(kPatternKinds, kind); }
std::optional<PatternKind> patternKindFromName(std::string_view text) { return find(kPatternKinds, text); }

std::string_view name(FactorKind kind) { return lookUp(kFactorKinds, kind); }
std::optional<FactorKind> factorKindFromName(std::string_view text) { return find(kFactorKinds, text); }

std::string_view name(ThresholdDirection direction) { return lookUp(kDirections, direction); }
std::optional<ThresholdDirection> thresholdDirectionFromName(std::string_view text) { return find(kDirections, text); }

std::string_view name(TextScale scale) { return lookUp(kScales, scale); }
std::optional<TextScale> textScaleFromName(std::string_view text) { return find(kScales, text); }

std::string_view name(TextRating rating) { return lookUp(kRatings, rating); }
std::optional<TextRating> textRatingFromName(std::string_view text) { return find(kRatings, text); }

std::string_view name(ActionKind kind) { return lookUp(kActionKinds, kind); }
std::optional<ActionKind> actionKindFromName(std::string_view text) { return find(kActionKinds, text); }

std::string_view name(AllowPart part) { return lookUp(kAllowParts, part); }
std::optional<AllowPart> allowPartFromName(std::string_view text) { return find(kAllowParts, text); }

std::string_view name(FunctionKind kind) { return lookUp(kFunctionKinds, kind); }
std::optional<FunctionKind> functionKindFromName(std::string_view text) { return find(kFunctionKinds, text); }

bool isBinary(Op op) { return op >= Op::Add && op <= Op::Iff; }

}  // namespace cbtl::ir
