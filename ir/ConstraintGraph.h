// ConstraintGraph.h — the compiler's output: plain, serialisable data that the runtime consumes.
//
// Variables of every task are instantiated here: top-level variables keep their names and are shared by
// all tasks; task variables keep theirs; a skill instance's variables are named "<instance>.<var>";
// family members are "name[member]". Constraints are hyperedges over variable ids, with their expression
// tree and source span. Top-level `forall` over a finite set is unrolled into one constraint per binding.
// Nothing here points into the AST: the runtime never sees compiler data structures.
//
// Spans are 1-based line/column pairs with the file path as written by the user.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::ir {

using VarId = std::uint32_t;

struct Span {
  std::string file;
  std::uint32_t line = 0, column = 0, endLine = 0, endColumn = 0;
};

// The discriminators below are enums; their names (as `cbtlc emit` prints them and a graph reader parses
// them) live in one table, ir/OpNames.h.

// What a type is. Error: a type the checker could not determine.
enum class TypeKind : std::uint8_t {
  Error,
  Real,
  Int,
  Bool,
  Text,
  Enum,
  Item,
  Vec,
  SE2,
  SE3,
  Conf,
  Set,
  Tuple,
  Range,
  Void
};

// Types as canonical spellings ("real", "vec<2>", "Conf<gen3>", "set<Book>", "Dip"), plus the kind.
struct TypeDesc {
  TypeKind kind = TypeKind::Void;
  std::string spelling;
};

// The node kinds of an expression tree, and which Expr fields each one uses (names in ir/OpNames.h).
// Keep Invalid last: ir/OpNames.cpp checks its table against it.
enum class Op : std::uint8_t {
  Num,      // number; text: its spelling as written (empty for computed numbers)
  Str,      // text: the string
  Bool,     // number: 1 or 0
  Var,      // id: the variable; text: its name
  Obs,      // text: the observation; a family's: one child, the index
  Const,    // text: the constant; a family's: one child, the index
  Enum,     // extra: the enum type, text: the member
  Item,     // extra: the item set, text: the entry
  EnumSet,  // text: an enum type used as the set of its members
  ItemSet,  // text: an item set used as the set of its entries
  Param,    // id: the generator or function parameter's index; text: its name
  Local,    // text: a quantifier's or loop's binder
  Family,   // text: the variable family; vars: all its members; one child, the index
  Call,     // text: the callee (a built-in or user function); children: the arguments
  Member,   // text: the field; one child, the base
  Index,    // children: the base, then the indices
  Neg,      // one child
  Not,      // one child
  Add,      // Add .. Iff: the binary operators, two children
  Sub,
  Mul,
  Div,
  Mod,
  Pow,
  Eq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  And,
  Or,
  Implies,
  Iff,
  Range,    // children: lo, hi
  In,       // children: the element, the set
  Forall,   // names: the binders; children: the set, the `where` (Bool true when absent), the body
  Exists,   // as Forall
  If,       // children: condition, then, else
  Tuple,    // children: the elements
  List,     // children: the elements
  Invalid,  // a name the compiler could not lower (text: the name)
};

struct Expr {
  Op op = Op::Invalid;
  TypeDesc type;
  double number = 0;
  std::string text;                // str value, names, member, callee
  std::string extra;               // enum type / item set / obs family
  std::int64_t id = -1;            // var id, param index
  std::vector<std::string> names;  // binder names
  std::vector<VarId> vars;         // family members
  std::vector<Expr> children;
};

struct Bound {
  std::optional<Expr> lo, hi;  // absent: unbounded
};

struct Domain {
  // real/int/vec/SE2/SE3: one bound per component (vec: N, SE2: x y yaw, SE3: x y z); enum/item/text/bool:
  // `set` lists the allowed values (absent: all values of the type); Conf: the robot's joint limits.
  std::vector<Bound> bounds;
  std::optional<Expr> set;
};

struct Variable {
  VarId id = 0;
  std::string name;  // unique within each task that includes it
  TypeDesc type;
  Domain domain;
  std::optional<Expr> init;
  std::string family;     // family name for family members, else empty
  std::string indexText;  // the member's index as text ("salt", "2")
  std::string scope;      // "global", "task:<name>" or "skill:<task>/<instance>"
  Span span;
};

struct Constraint {
  std::uint32_t id = 0;
  std::string name;         // declared name, or "<scope>#<n>"; unrolled copies get "[binding]"
  std::vector<VarId> vars;  // the hyperedge, sorted, unique
  Expr expr;
  std::string scope;
  Span span;
};

struct Sampler {
  std::uint32_t id = 0;
  std::string sampler;  // "uniform" or an extern sampler's name
  std::vector<VarId> writes;
  std::vector<VarId> reads;
  std::vector<Expr> args;
  std::string scope;
  Span span;
};

struct Cost {
  bool maximize = false;
  Expr expr;
  std::vector<VarId> vars;
  Span span;
};

struct Param {
  std::string name;
  TypeDesc type;
};

enum class PatternKind : std::uint8_t { Glob, Regex };

struct Pattern {
  std::string param;
  std::uint32_t paramIndex = 0;
  PatternKind kind = PatternKind::Glob;
  std::string text;
  Span span;
};

enum class FactorKind : std::uint8_t { Interval, Threshold, Table, Text };
// None: the factor is not a threshold (printed as the empty name).
enum class ThresholdDirection : std::uint8_t { None, Above, Below };
enum class TextScale : std::uint8_t { Absolute, Relative };
enum class TextRating : std::uint8_t { Digits, Options };

// One part of a text model's context (`context: [foodOnPlate, mealSetting]`): the situation the subject is judged
// in, as the paper's ConstraintPrompt takes the observation with the values. `value` is an observation or a
// generator parameter, of a discrete scalar type (text, enum, item, bool, int).
struct ContextEntry {
  std::string name;                 // as written; the key the models see
  Expr value;                       // the name, lowered (Obs or Param)
  std::vector<std::string> params;  // generator parameters it reads (a learning rule must bind them)
};

struct ModelFactor {
  std::string label;  // factor name (defaults to the kind, numbered if repeated)
  FactorKind kind = FactorKind::Interval;
  std::optional<Expr> feature;                              // interval/threshold feature; table key; text subject
  double lo = 0, hi = 0;                                    // interval/threshold prior bounds
  ThresholdDirection direction = ThresholdDirection::None;  // threshold: Above | Below
  std::string prompt, learning;                             // text
  TextScale scale = TextScale::Absolute;                    // text
  TextRating rating = TextRating::Digits;                   // text
  std::vector<ContextEntry> context;                        // text: what the subject is judged in
  std::vector<std::string> params;                          // generator parameters the feature reads
  Span span;
};

struct LearnLabel {
  std::string factor;  // empty: the single factor
  Expr value;
};

struct LearnRule {
  std::string event;
  std::vector<std::string> binders;  // "_" for ignored positions
  std::vector<std::string> binds;    // per binder: parameter/key it binds, or "" (local)
  std::vector<LearnLabel> labels;
  std::optional<Expr> condition;
  Span span;
};

// A `per` key: the instances of a generator share one model per distinct value of their keys. A key is a
// parameter or a capture named by `name`, or an expression over the parameters and observations (`name` is then
// its source text, as "kindOf[p]"). Model keys in profiles are the rendered key values joined by '|'.
struct PerKey {
  std::string name;
  std::optional<Expr> expr;         // set for an expression key
  std::vector<std::string> params;  // generator parameters the expression reads (a learning rule binds them)
};

struct Generator {
  std::string name;
  std::vector<Param> params;  // arity = params.size()
  std::vector<Pattern> patterns;
  std::vector<std::string> captures;
  std::vector<PerKey> perKeys;
  std::vector<ModelFactor> factors;
  std::optional<Expr> guard;  // bool over the parameters; false: the constraint does not apply
  double accept = 0.5;
  double fallback = 0.5;
  // `explore accepted`: CBTL's exploration keeps this constraint (P >= accept) while it maximizes entropy, and the
  // constraint's entropy is that of its maximum-likelihood reading (none before an interval's first positive);
  // false (`explore anywhere`, the default): the paper's exploration, the constraint only steers the entropy, by
  // its full posterior.
  bool exploreAccepted = false;
  std::vector<LearnRule> learnRules;
  Span span;
};

// Allow: a skill's declared exception to the world's clearances, in force for the actions of its body.
enum class ActionKind : std::uint8_t { Call, For, If, Block, Allow };

// The part of the robot an exception is for: any robot body, the gripper (end effector and fingers), or the object
// the robot holds.
enum class AllowPart : std::uint8_t { Robot, Gripper, Held };

// `allow <part> near <target> <length> { ... }` (the part may come to `length` of the target) or
// `allow <part> touch <target> <length> { ... }` (it may touch the target and sink into it by `length`).
struct Allowance {
  AllowPart part = AllowPart::Held;
  std::string clearance;       // the target when it is a declared clearance (ConstraintGraph::clearances), by name
  std::optional<Expr> target;  // otherwise: a text naming a scene body (with the bodies below it) or a scene geom
  double separation = 0;       // metres the part keeps at least; negative: the depth it may sink (`touch`)
};

struct Action {
  ActionKind kind = ActionKind::Block;
  std::string name;
  std::vector<Expr> args;
  std::vector<std::string> binders;
  std::optional<Expr> set;         // for
  std::optional<Expr> condition;   // if
  std::optional<Allowance> allow;  // allow
  std::vector<Action> body, elseBody;
  Span span;
};

// `clearance <name>: "body", ... >= <length>;` — a class of the world's bodies and the distance the robot, and what
// it holds, keeps from every one of them along every motion (a hard constraint; skills may declare exceptions).
struct Clearance {
  std::string name;
  std::vector<std::string> bodies;  // scene body names; each covers the bodies attached below it too
  double distance = 0;              // metres, >= 0
  Span span;
};

struct SkillInstance {
  std::string skill;
  std::string name;
  std::vector<VarId> vars;    // the instance's own variables
  std::vector<VarId> params;  // task variables bound to the skill's parameters
  std::vector<std::uint32_t> constraints;
  std::vector<std::uint32_t> samplers;
  std::vector<Action> actions;  // Var references use the task's ids
  Span span;
};

struct Task {
  std::string name;
  std::vector<VarId> vars;  // every variable of the CSP: global, task, skill instances
  std::vector<std::uint32_t> constraints;
  std::vector<std::uint32_t> samplers;
  std::vector<std::uint32_t> costs;
  std::vector<SkillInstance> instances;
  bool implicit = false;  // the `main` task of a file without tasks
  Span span;
};

struct Enum {
  std::string name;
  std::vector<std::string> members;
  Span span;
};

struct ItemField {
  std::string name;
  TypeDesc type;
};
struct ItemType {
  std::string name;
  std::vector<ItemField> fields;
  Span span;
};
struct ItemEntry {
  std::string name;
  std::vector<std::pair<std::string, Expr>> fields;
};
struct ItemSet {
  std::string name;
  std::string itemType;
  std::vector<ItemEntry> entries;
  Span span;
};

struct Constant {
  std::string name;
  TypeDesc type;
  std::string indexSet;  // family: the index set's spelling
  Expr value;
  Span span;
};

struct Observation {
  std::string name;
  TypeDesc type;
  std::optional<Expr> indexSet;
  Span span;
};

// Feedback: an event declaration (ConstraintGraph::feedback), not callable.
enum class FunctionKind : std::uint8_t { Function, Sampler, Action, Feedback };

struct Function {
  std::string name;
  FunctionKind kind = FunctionKind::Function;
  bool isExtern = true;
  std::vector<std::string> typeParams;
  std::vector<Param> params;
  TypeDesc result;
  std::optional<Expr> body;
  Span span;
};

struct Robot {
  std::string name;
  int dof = 0;
};

struct ConstraintGraph {
  std::string domain;
  std::string world;  // as written, relative to the root file
  // An external simulator's command, as written (run in the root file's folder); empty: none.
  std::string simulator;
  Span simulatorSpan;
  std::vector<Robot> robots;
  std::vector<Clearance> clearances;
  std::vector<Enum> enums;
  std::vector<ItemType> itemTypes;
  std::vector<ItemSet> itemSets;
  std::vector<Constant> constants;
  std::vector<Observation> observations;
  std::vector<Function> feedback;  // kind Feedback: events with parameters
  std::vector<Function> functions;
  std::vector<Variable> variables;
  std::vector<Constraint> constraints;
  std::vector<Sampler> samplers;
  std::vector<Cost> costs;
  std::vector<Generator> generators;
  std::vector<std::string> skills;
  std::vector<Task> tasks;
};

}  // namespace cbtl::ir
