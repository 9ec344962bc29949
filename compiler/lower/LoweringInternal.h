// LoweringInternal.h — the `lower` pass's lowerer, shared by its implementation files only.
//
// Internal to compiler/lower: callers use lowerToGraph() (Lowering.h). The lowerer is one class because
// its concerns call each other recursively (declarations, statements and actions lower expressions,
// expressions evaluate family indices at compile time, a task lowers the body of each skill instance) and
// share the pass's state (the graph being built, the global context every task starts from, the graph's
// running size). Its member functions are implemented by concern:
//   Lowering.cpp            the entry point, the order of the pass, read sets and the graph-size limits
//   LoweringConstEval.cpp   compile-time values: family indices, finite sets, `where` conditions
//   LoweringExprs.cpp       expressions (names, family members, calls) and the variables a context sees
//   LoweringDecls.cpp       top-level declarations (robots, enums, items, constants, observations, feedback,
//                           functions) and variables with their families and domains
//   LoweringBodies.cpp      the body of a scope: domain constraints, `require` (unrolling top-level
//                           `forall`), `sample` and `cost`
//   LoweringTasks.cpp       tasks, their skill instances and the instances' actions
//   LoweringGenerators.cpp  personalized generators: patterns, model factors, guards, learning rules, W0401
//   LoweringLimits.cpp      quantifier nests and generator instances, measured for CompileLimits
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/driver/CompileLimits.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"
#include "ir/ConstraintGraph.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::detail {

// A value known at compile time, used for family indices and quantifier bindings.
struct CVal {
  enum class Kind { Enum, Int, Item, Text, None } kind = Kind::None;
  std::string text;  // member / entry name, the integer as text, or the string
  long long number = 0;
  const Decl* decl = nullptr;  // EnumDecl or ItemsDecl
  int index = -1;
};

// The compile-time value of member `index` of `en` and of entry `index` of `items`. Two values are the
// same member only when both their declaration and index match (LoweringConstEval.cpp, decide).
CVal enumMemberValue(const EnumDecl& en, int index);
CVal itemEntryValue(const ItemsDecl& items, int index);

// The graph's description of a semantic type; null (no type) is void.
ir::TypeDesc typeDesc(const Type* t);

class Lowerer {
 public:
  Lowerer(const GlobalSymbols& symbols, const SourceManager& sources, DiagnosticEngine& diags, ir::ConstraintGraph& g)
      : symbols_(symbols), sources_(sources), diags_(diags), g_(g) {}

  // Lowers every module (root first) into the graph given at construction; reports into `diags`. The
  // graph is complete only if no error was reported.
  void run(const std::vector<std::unique_ptr<Module>>& modules);

 private:
  // Where a body is being lowered. Each task and skill instance has its own; top-level declarations,
  // function bodies, domains and generators use an empty one.
  struct Ctx {
    std::string scope;
    std::string prefix;                                            // "<instance>." for skill instances
    std::map<const Decl*, std::map<std::string, ir::VarId>> vars;  // VarDecl -> member text ("" if scalar) -> id
    const SkillDecl* skill = nullptr;
    std::vector<std::optional<ir::Expr>> skillParams;  // lowered expression per skill parameter (a var node)
    std::map<const BinderDecl*, CVal> env;             // binders bound to one value by unrolling or `for`
  };

  // --- Lowering.cpp: spans, read sets, size limits ---
  ir::Span span(SourceRange r) const;
  // Read sets as the runtime evaluates them: with every called function's body inlined (ir/ReadSet.h).
  // Run once everything is lowered, so a function declared after its caller is followed too.
  void followCallsInReadSets();

  // Families, unrolled foralls, sample `for` sets and skill instances multiply declarations. These limits
  // turn a blow-up (a typo such as 0 .. 1000000, or a fuzzer's input) into a diagnostic instead of an
  // exhausted machine. kMaxSetSize bounds one integer range used as a family index or `for` set;
  // kMaxGraphSize bounds the whole graph in units of one variable, constraint, sampler, cost or action plus
  // one per expression node. Real programs stay orders of magnitude below both.
  // (The values are in compiler/driver/CompileLimits.h.)
  static constexpr std::size_t kMaxSetSize = CompileLimits::kMaxSetSize;
  static constexpr std::size_t kMaxGraphSize = CompileLimits::kMaxGraphSize;
  // A top-level forall is unrolled only while the number of instances stays below this; beyond it the
  // constraint keeps its quantifier (same meaning, one hyperedge).
  static constexpr std::size_t kMaxUnrolled = CompileLimits::kMaxUnrolled;

  // The nodes the runtime builds for `x`: each call of a user function counts with its inlined body
  // (FuncDecl::inlinedNodes, measured by check-types).
  std::size_t nodeCount(const ir::Expr& x) const;
  std::size_t actionSize(const ir::Action& a) const;
  // Adds `units` to the graph's size; false (with E0317 reported once) when the graph is too large.
  bool grow(std::size_t units, SourceRange at);
  // E0317 for a set of more than kMaxSetSize members; `what` names its use.
  void tooManyMembers(SourceRange at, const char* what);

  // --- LoweringConstEval.cpp: compile-time values ---
  // The value of `e` if it is known at compile time (a literal, integer arithmetic that fits in 64 bits,
  // an enum member, an item entry, a bound binder or an unindexed constant), else nullopt.
  std::optional<CVal> evalConst(const Expr* e, const Ctx& ctx);
  std::optional<CVal> evalConstArithmetic(const Expr& e, const Ctx& ctx);
  std::optional<CVal> evalConstName(const Expr& e, const Ctx& ctx);
  // The members of a compile-time finite set, or nullopt if it is not known at compile time or (then
  // *tooLarge is set) is an integer range of more than kMaxSetSize members.
  std::optional<std::vector<CVal>> enumerate(const Expr* set, const Ctx& ctx, bool* tooLarge = nullptr);
  std::optional<std::vector<CVal>> enumerateRange(const Expr& range, const Ctx& ctx, bool* tooLarge);
  // Decides a `where` condition at compile time when it only compares bound values (null is true).
  std::optional<bool> decide(const Expr* e, const Ctx& ctx);
  std::optional<bool> decideComparison(const Expr& e, const Ctx& ctx);
  // The literal node of a compile-time value of type `t`.
  static ir::Expr constNode(const CVal& v, const Type* t);

  // --- LoweringExprs.cpp: expressions ---
  // Lowers `e` (null is `true`); binders bound in ctx.env become literals, skill parameters the instance's
  // argument.
  ir::Expr lower(const Expr* e, Ctx& ctx);
  ir::Expr& lowerName(const Expr& e, Ctx& ctx, ir::Expr& x);
  // `family[index]`: one member's variable when the index is known at compile time, else a family node
  // that reads every member.
  ir::Expr& lowerFamilyIndex(const Expr& e, Ctx& ctx, ir::Expr& x);
  // The arguments in parameter order (positional first, then named; missing ones left out). Without a
  // callee (an extern without declaration) in the order written.
  static std::vector<const Arg*> orderedArgs(const CallableDecl* callee, const std::vector<Arg>& args);
  // Variables visible in a context: its own, then the global ones.
  std::map<std::string, ir::VarId> lookupVars(const Decl* decl, const Ctx& ctx);
  ir::VarId varId(const Decl* decl, const std::string& member, Ctx& ctx);
  // The hyperedge of an expression: every variable it names, family members included.
  static void collectVars(const ir::Expr& x, std::set<ir::VarId>& out);

  // --- LoweringDecls.cpp: top-level declarations and variables ---
  void declareTop(const Decl& d);
  // A checked length (unit m, cm or mm) in metres.
  static double metres(const Length& l);
  void declareItemSet(const ItemsDecl& items);
  void declareCallable(const CallableDecl& c);
  // Function bodies may read global variables, so they are lowered once those exist.
  void lowerFunctionBodies();
  // Adds one graph variable per member of `v` (one for a scalar) to the graph, ctx.vars and `out`.
  void lowerVar(const VarDecl& v, Ctx& ctx, std::vector<ir::VarId>& out);
  void checkUniformBounds(const SampleDecl& s, const std::set<ir::VarId>& writes);
  // The members of `v` (member text, its value); false after reporting a family that cannot be expanded.
  bool familyMembers(const VarDecl& v, const Ctx& ctx,
                     std::vector<std::pair<std::string, std::optional<CVal>>>& members);
  ir::Domain lowerDomain(const VarDecl& v, Ctx& ctx);
  void reportEmptyRange(const VarDecl& v, const ir::Domain& d);
  std::optional<double> foldedNumber(const ir::Expr& e, int depth = 0) const;

  // --- LoweringBodies.cpp: the body of a scope ---
  // Lowers a scope's declarations (variables first, then statements) and appends the ids made to the lists.
  void lowerBody(const std::vector<const Decl*>& body, Ctx& ctx, std::vector<ir::VarId>& vars,
                 std::vector<std::uint32_t>& constraints, std::vector<std::uint32_t>& samplers,
                 std::vector<std::uint32_t>& costs);
  std::uint32_t addConstraint(std::string name, ir::Expr expr, const std::string& scope, SourceRange at);
  // Unrolls nested top-level foralls over compile-time sets. `instances` is the number of copies the
  // enclosing levels already make; a level that would take the total past kMaxUnrolled keeps its quantifier.
  void lowerRequire(const RequireDecl& r, Ctx& ctx, std::vector<std::uint32_t>& out, const std::string& base,
                    const Expr* cond, std::string suffix, std::size_t instances = 1);
  // One level of lowerRequire's unrolling; false if `cond` cannot be unrolled (it is then kept whole).
  bool unrollForall(const RequireDecl& r, Ctx& ctx, std::vector<std::uint32_t>& out, const std::string& base,
                    const Expr& cond, const std::string& suffix, std::size_t instances);
  void lowerSample(const SampleDecl& s, Ctx& ctx, std::vector<std::uint32_t>& out);
  void lowerSampleInstance(const SampleDecl& s, Ctx& inner, std::vector<std::uint32_t>& out);
  void lowerCost(const CostDecl& c, Ctx& ctx, std::vector<std::uint32_t>& out);

  // --- LoweringTasks.cpp: tasks, skill instances, actions ---
  // Adds the task (the global declarations, its own, then each skill instance's) and records the skills
  // it runs in `usedSkills`.
  void lowerTask(const TaskDecl& t, std::set<std::string>& usedSkills);
  // Lowers one skill instance of a task whose own context is `ctx` and appends its ids to `task`.
  void lowerSkillInstance(const TaskDecl& t, const SkillInstance& inst, Ctx& ctx, ir::Task& task);
  ir::Action lowerAction(const ActionStmt& s, Ctx& ctx);
  // `allow PART near|touch TARGET LENGTH`: the exception, its separation signed by the mode.
  ir::Allowance lowerAllowance(const AllowClause& a, Ctx& ctx);

  // --- LoweringLimits.cpp: quantifier nests and generator instances (CompileLimits) ---
  // E0320 when the nest of quantifiers that starts at `quantifier` ranges over more than
  // kMaxQuantifierBindings combinations (once per quantifier; nothing inside an outer nest being lowered).
  void checkQuantifierNest(const Expr& quantifier, const Ctx& ctx);
  // The number of members of a set known at compile time; 1 for one that is not (it is not counted).
  std::size_t setSize(const Expr* set, const Ctx& ctx);
  // The largest product of set sizes along a path of nested quantifiers in `e`, calls followed into function
  // bodies; saturates at SIZE_MAX. With `report`, E0320 at the innermost quantifier that goes over the limit.
  std::size_t quantifierBindings(const Expr* e, const Ctx& ctx, bool report);
  std::size_t functionBindings(const FuncDecl& f);
  // E0418 once the instances the runtime would make for the generators so far, or the steps to find them,
  // exceed their limits; counted by replaying the runtime's matching without building instances.
  void checkGeneratorInstances(const PersonalDecl& p, const ir::Generator& g);
  void reportTooManyInstances(const PersonalDecl& p, const std::string& task, bool instances,
                              const std::vector<const std::vector<ir::VarId>*>& candidates);
  // The variables of task `task` (an index into the graph's tasks) whose type is spelled `type`, in order.
  const std::vector<ir::VarId>& candidatesOfType(std::size_t task, const std::string& type);

  // --- LoweringGenerators.cpp: personalized generators ---
  void lowerGenerator(const PersonalDecl& p);
  // A generator belongs to no task: its expressions are lowered in one empty context, `none`.
  ir::ModelFactor lowerFactor(const PersonalDecl& p, const ModelFactor& f, Ctx& none);
  // A text model's `context:` names, lowered in the generator's scope (observations and parameters).
  void lowerTextContext(const PersonalDecl& p, const Expr& context, ir::ModelFactor& mf, Ctx& none);
  ir::LearnRule lowerLearnRule(const PersonalDecl& p, const LearnRule& rule, Ctx& none);
  // W0401: some parameter's pattern (with its type) matches no variable of any task.
  void warnIfUnmatched(const PersonalDecl& p, const ir::Generator& g);
  void warnIfNeverTogether(const PersonalDecl& p, const ir::Generator& g);

  const GlobalSymbols& symbols_;
  const SourceManager& sources_;
  DiagnosticEngine& diags_;
  ir::ConstraintGraph& g_;
  Ctx globalCtx_;
  std::vector<std::pair<std::size_t, const CallableDecl*>> pendingBodies_;  // function index, its declaration
  std::map<std::string, std::size_t> inlinedNodes_;  // user function name -> FuncDecl::inlinedNodes
  int quantifierNesting_ = 0;                        // quantifiers being lowered around the current expression
  std::set<const Expr*> quantifiersReported_;        // E0320 once per quantifier (unrolling lowers copies)
  std::map<const FuncDecl*, std::size_t> functionBindings_;
  std::size_t generatorInstances_ = 0, generatorMatchSteps_ = 0;
  bool generatorsTooLarge_ = false;  // E0418 reported: later generators are not counted
  std::map<std::size_t, std::map<std::string, std::vector<ir::VarId>>> candidatesByTask_;
  std::size_t graphSize_ = 0;
  bool tooLarge_ = false;
  std::vector<const VarDecl*> declOf_;  // the declaration of each graph variable, by id
  std::vector<ir::VarId> globalVars_;
  std::vector<std::uint32_t> globalConstraints_, globalSamplers_, globalCosts_;
};

}  // namespace cbtl::detail
