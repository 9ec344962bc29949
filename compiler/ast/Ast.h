// Ast.h — the abstract syntax tree of a .cbtl module.
//
// Built once from the ANTLR parse tree (AstBuilder), then only annotated by the semantic passes: name
// resolution fills `Expr::ref` and `TypeRef::resolved`, type checking fills `Expr::type`. Every node has
// a SourceRange. Nodes are owned by their parent through unique_ptr; cross references (a name to its
// declaration) are plain pointers that stay valid as long as the owning Module lives.
#pragma once

#include "compiler/source/SourceManager.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace cbtl {

struct Type;  // sema/Type.h
struct Decl;
struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Ident {
  std::string name;
  SourceRange range;
};

// ---------------------------------------------------------------------------------------------
// Types as written
// ---------------------------------------------------------------------------------------------

// real | vec<3> | Conf<gen3> | set<Book> | Dip ; an argument is either a number or a type.
struct TypeRef {
  Ident name;
  struct Arg {
    bool isNumber = false;
    double number = 0;
    std::unique_ptr<TypeRef> type;
    SourceRange range;
  };
  std::vector<Arg> args;
  SourceRange range;
  const Type* resolved = nullptr;  // set by name resolution
};

// ---------------------------------------------------------------------------------------------
// Expressions
// ---------------------------------------------------------------------------------------------

enum class ExprKind {
  Number,
  String,
  Bool,
  Name,
  Member,
  Call,
  Index,
  Unary,
  Binary,
  Range,
  In,
  Quantifier,
  If,
  Tuple,
  List,
};

enum class UnaryOp { Neg, Not };
enum class BinaryOp { Add, Sub, Mul, Div, Mod, Pow, Eq, Ne, Lt, Le, Gt, Ge, And, Or, Implies, Iff };
enum class QuantKind { Forall, Exists };

const char* toString(BinaryOp op);
const char* toString(UnaryOp op);

// What a name refers to after name resolution.
enum class RefKind {
  Unresolved,
  Const,        // decl: ConstDecl
  EnumType,     // decl: EnumDecl (as an expression: the set of its members)
  EnumMember,   // decl: EnumDecl, index: member
  ItemSet,      // decl: ItemsDecl
  ItemEntry,    // decl: ItemsDecl, index: entry
  Observation,  // decl: ObserveDecl
  Variable,     // decl: VarDecl
  Param,        // decl: the owning Function/Personal/Skill decl, index: parameter position
  Binder,       // a quantifier / learn / for binder; binder points at the BinderDecl
  Function,     // decl: FuncDecl
  Sampler,      // decl: SamplerDecl
  Action,       // decl: ActionDecl
  Feedback,     // decl: FeedbackDecl
  Builtin,      // a compiler built-in constant (pi) or function (box, uniform); index: BuiltinId
};

struct BinderDecl;

struct NameRef {
  RefKind kind = RefKind::Unresolved;
  const Decl* decl = nullptr;
  const BinderDecl* binder = nullptr;
  int index = -1;
};

struct Arg {
  Ident name;  // empty for positional arguments
  ExprPtr value;
  SourceRange range;
};

// `a, b in S` — one or more names ranging over a set expression.
struct BinderDecl {
  Ident name;
  const Type* type = nullptr;  // element type, set by type checking
};
struct Binder {
  std::vector<std::unique_ptr<BinderDecl>> names;
  ExprPtr set;
  SourceRange range;
};

struct Expr {
  ExprKind kind;
  SourceRange range;

  double number = 0;      // Number
  bool boolean = false;   // Bool
  std::string text;       // String value; Name / Member identifier
  SourceRange nameRange;  // Member: the member name
  UnaryOp unaryOp = UnaryOp::Neg;
  BinaryOp binaryOp = BinaryOp::Add;
  QuantKind quant = QuantKind::Forall;

  // Operands: Unary {x}; Binary/Range/In {lhs, rhs}; Member {object}; Call {callee}; Index {object,
  // indices...}; If {cond, then, else}; Tuple/List elements; Quantifier {where?, body} (where may be null).
  std::vector<ExprPtr> operands;
  std::vector<Arg> args;           // Call arguments
  std::unique_ptr<Binder> binder;  // Quantifier

  NameRef ref;                 // Name (and Call's callee name) after resolution
  const Type* type = nullptr;  // after type checking

  Expr(ExprKind k, SourceRange r) : kind(k), range(r) {}
};

// ---------------------------------------------------------------------------------------------
// Declarations
// ---------------------------------------------------------------------------------------------

enum class DeclKind {
  Domain,
  Import,
  World,
  Simulator,
  Robot,
  Clearance,
  Const,
  Enum,
  ItemType,
  ItemSet,
  Observe,
  Feedback,
  Function,
  Sampler,
  Action,
  Var,
  Require,
  Sample,
  Cost,
  Personal,
  Skill,
  Task,
};

const char* toString(DeclKind kind);

struct Decl {
  explicit Decl(DeclKind k) : kind(k) {}
  virtual ~Decl() = default;
  DeclKind kind;
  Ident name;  // empty for anonymous declarations (import, world, require without a name, sample, cost)
  SourceRange range;
};

struct Param {
  Ident name;
  TypeRef type;
};

// [Ingredient] or [i in Ingredient] or [0 .. 3]
struct IndexSpec {
  Ident binder;  // optional name for the index
  ExprPtr set;
  SourceRange range;
  const Type* elementType = nullptr;  // set by type checking
};

struct FieldInit {
  Ident name;
  ExprPtr value;
};

struct DomainDecl : Decl {
  DomainDecl() : Decl(DeclKind::Domain) {}
};

struct ImportDecl : Decl {
  ImportDecl() : Decl(DeclKind::Import) {}
  bool isPath = false;  // import "file.cbtl" vs import std.name
  std::string target;   // "std.geometry" or the path text
  SourceRange targetRange;
};

struct WorldDecl : Decl {
  WorldDecl() : Decl(DeclKind::World) {}
  std::string path;
  SourceRange pathRange;  // the string literal
};

struct SimulatorDecl : Decl {
  SimulatorDecl() : Decl(DeclKind::Simulator) {}
  std::string command;  // run with /bin/sh -c in the folder of the root file
};

struct RobotDecl : Decl {
  RobotDecl() : Decl(DeclKind::Robot) {}
  std::vector<FieldInit> fields;
  int dof = 0;  // from the `dof` field, set by type checking
};

// A distance as written: `5 cm`, `0.05 m`, `12.5 mm`. The unit is checked by check-types (m, cm or mm; a missing
// unit or a negative value is an error there) and the value converted to metres by lowering.
struct Length {
  double value = 0;       // the number as written, negated when a minus sign was written
  std::string spelling;   // the number as written (without the sign), for messages
  bool negative = false;  // a minus sign was written
  Ident unit;             // empty name: no unit written
  SourceRange range;      // the whole length, sign and unit included
};

// `clearance person: "user", "user_head" >= 5 cm;` — a class of scene bodies (each with the bodies attached below
// it) and the distance the robot and what it holds keep from them. The body names are checked against the world
// file by check-world.
struct ClearanceDecl : Decl {
  ClearanceDecl() : Decl(DeclKind::Clearance) {}
  std::vector<std::string> bodies;      // decoded string literals
  std::vector<SourceRange> bodyRanges;  // one per body, the literal with its quotes
  Length distance;
};

struct ConstDecl : Decl {
  ConstDecl() : Decl(DeclKind::Const) {}
  std::unique_ptr<IndexSpec> index;
  std::unique_ptr<TypeRef> type;  // optional
  ExprPtr value;
  const Type* valueType = nullptr;  // element type for families
};

struct EnumDecl : Decl {
  EnumDecl() : Decl(DeclKind::Enum) {}
  std::vector<Ident> members;
};

struct ItemTypeDecl : Decl {
  ItemTypeDecl() : Decl(DeclKind::ItemType) {}
  std::vector<Param> fields;
};

struct ItemEntry {
  Ident name;
  std::vector<FieldInit> fields;
  SourceRange range;
};

struct ItemsDecl : Decl {
  ItemsDecl() : Decl(DeclKind::ItemSet) {}
  TypeRef itemType;
  std::vector<ItemEntry> entries;
};

struct ObserveDecl : Decl {
  ObserveDecl() : Decl(DeclKind::Observe) {}
  std::unique_ptr<IndexSpec> index;
  TypeRef type;
};

struct FeedbackDecl : Decl {
  FeedbackDecl() : Decl(DeclKind::Feedback) {}
  std::vector<Param> params;
};

// extern fn / fn / extern sampler / extern action share this shape.
struct CallableDecl : Decl {
  explicit CallableDecl(DeclKind k) : Decl(k) {}
  bool isExtern = false;
  std::vector<Ident> typeParams;
  std::vector<Param> params;
  std::unique_ptr<TypeRef> result;  // null for actions
  ExprPtr body;                     // user functions only
};
struct FuncDecl : CallableDecl {
  FuncDecl() : CallableDecl(DeclKind::Function) {}
  // Set by check-types: the expression nodes of the body with every call in it inlined, as the runtime builds it
  // (0 when not measured: extern, recursive, or over a limit, which are errors).
  std::size_t inlinedNodes = 0;
};
struct SamplerDecl : CallableDecl {
  SamplerDecl() : CallableDecl(DeclKind::Sampler) {}
};
struct ActionDecl : CallableDecl {
  ActionDecl() : CallableDecl(DeclKind::Action) {}
};

struct VarDecl : Decl {
  VarDecl() : Decl(DeclKind::Var) {}
  std::unique_ptr<IndexSpec> index;
  TypeRef type;
  ExprPtr domain;  // optional `in ...`
  ExprPtr init;    // optional `= ...`
};

struct RequireDecl : Decl {
  RequireDecl() : Decl(DeclKind::Require) {}
  ExprPtr condition;
};

struct SampleDecl : Decl {
  SampleDecl() : Decl(DeclKind::Sample) {}
  std::vector<ExprPtr> targets;
  Ident sampler;
  NameRef samplerRef;
  bool hasArgs = false;
  std::vector<Arg> args;
  std::unique_ptr<Binder> forBinder;  // optional `for i in S`
};

struct CostDecl : Decl {
  CostDecl() : Decl(DeclKind::Cost) {}
  bool maximize = false;
  ExprPtr value;
};

// --- personalized constraint generators ----------------------------------------------------------

enum class PatternKind { Glob, Regex };

struct PatternClause {
  Ident param;
  PatternKind kind = PatternKind::Glob;
  std::string pattern;
  SourceRange patternRange;
  int paramIndex = -1;  // set by the generator checker
};

struct ModelFactor {
  Ident label;  // optional factor name
  Ident kind;   // interval | threshold | table | text
  std::vector<Arg> args;
  SourceRange range;
};

struct LearnLabel {
  Ident factor;  // optional
  ExprPtr value;
};

struct LearnRule {
  Ident event;
  NameRef eventRef;
  std::vector<std::unique_ptr<BinderDecl>> binders;  // "_" binders keep an empty name
  std::vector<SourceRange> binderRanges;
  std::vector<LearnLabel> labels;
  ExprPtr condition;  // optional
  SourceRange range;
};

// A `per` key as written: a bare name (a capture of the patterns or a parameter) or an expression over the
// generator's parameters and the observations (`per kindOf[p]`, `per p.kind`). The instances of a generator share
// one model per distinct value of their keys.
struct PerKey {
  Ident spelling;  // the source text with its whitespace collapsed (the key's name in messages and profiles)
  ExprPtr expr;    // always set; a bare name that names a capture stays unresolved
  bool bareName() const { return expr && expr->kind == ExprKind::Name; }
};

struct PersonalDecl : Decl {
  PersonalDecl() : Decl(DeclKind::Personal) {}
  std::vector<Param> params;
  std::vector<PatternClause> patterns;
  std::vector<SourceRange> whenRanges;  // one per `when` clause (more than one is an error)
  std::vector<ModelFactor> factors;
  std::vector<PerKey> perKeys;
  std::vector<SourceRange> modelRanges;  // one per `model` clause
  std::vector<ExprPtr> accepts;
  std::vector<ExprPtr> fallbacks;
  // `explore accepted;` / `explore anywhere;` (the mode's name and where it was written); at most one.
  std::vector<Ident> explores;
  // `if EXPR;` guards over the parameters: where one is false the constraint does not apply (holds, with
  // no uncertainty). Several guards are conjoined.
  std::vector<ExprPtr> guards;
  std::vector<LearnRule> learnRules;
  // Capture names from glob patterns, in order of first appearance (set by the generator checker).
  std::vector<Ident> captures;
};

// --- skills and tasks -------------------------------------------------------------------------------

enum class ActionStmtKind { Call, For, If, Block, Allow };

// `allow PART MODE TARGET LENGTH { ... }`: a scoped exception to the world's clearances for the actions of its body.
// The part and the mode are written as names (robot | gripper | held, near | touch) and checked by check-types.
struct AllowClause {
  Ident part;
  Ident mode;
  ExprPtr target;  // a bare clearance name, or a text expression naming a scene body or geom
  // Set by name resolution when the target is a bare name that names a declared clearance (the target expression
  // is then left unresolved and untyped).
  const ClearanceDecl* clearance = nullptr;
  Length length;
};

struct ActionStmt {
  ActionStmtKind kind = ActionStmtKind::Call;
  SourceRange range;
  Ident callee;  // Call
  NameRef calleeRef;
  std::vector<Arg> args;
  std::unique_ptr<Binder> forBinder;   // For
  ExprPtr condition;                   // If
  std::unique_ptr<AllowClause> allow;  // Allow
  std::vector<std::unique_ptr<ActionStmt>> body;
  std::vector<std::unique_ptr<ActionStmt>> elseBody;
  bool hasElse = false;
};

struct SkillDecl : Decl {
  SkillDecl() : Decl(DeclKind::Skill) {}
  std::vector<Param> params;
  std::vector<std::unique_ptr<Decl>> body;           // Var, Require, Sample, Cost
  std::vector<std::unique_ptr<ActionStmt>> actions;  // the `do` statements, in order
};

struct SkillInstance {
  Ident skill;
  const SkillDecl* skillDecl = nullptr;
  bool hasArgs = false;
  std::vector<Arg> args;
  Ident alias;
  SourceRange range;
  const std::string& instanceName() const { return alias.name.empty() ? skill.name : alias.name; }
};

struct TaskDecl : Decl {
  TaskDecl() : Decl(DeclKind::Task) {}
  std::vector<std::unique_ptr<Decl>> body;  // Var, Require, Sample, Cost
  std::vector<SkillInstance> instances;     // all `run` sequences, in order
};

// ---------------------------------------------------------------------------------------------
// A module: one parsed file
// ---------------------------------------------------------------------------------------------

struct Module {
  FileId file = kNoFile;
  std::string domainName;  // from `domain NAME;`, may be empty
  bool isStd = false;      // a standard-library module (std.NAME), embedded or read from --stdlib
  std::vector<std::unique_ptr<Decl>> decls;
};

}  // namespace cbtl
