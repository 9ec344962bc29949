// TypeCheckerInternal.h — the `check-types` pass's checker, shared by its implementation files only.
//
// Internal to compiler/sema: callers use checkTypes() (TypeChecker.h). The checker is one class because
// its concerns call each other recursively (typing a name checks a constant's declaration on first use,
// declarations type their expressions, calls check their arguments) and share the pass's state (the
// domain flag, the constants being checked). Its member functions are implemented by concern:
//   TypeChecker.cpp       the entry point and the declaration dispatch
//   TypeCheckerFunctions.cpp  the call graph of user functions: recursion and inlined size
//   TypeCheckerExprs.cpp  expression typing (names, members, operators, indexing, lists, binders)
//   TypeCheckerCalls.cpp  calls against extern and user signatures (argument matching, unification)
//   TypeCheckerDecls.cpp  constants, index sets, variables and their domains, samples, items, robots,
//                         generators
//   TypeCheckerTasks.cpp  skill bodies, action blocks and task skill instances
//   TypeCheckerClearances.cpp  clearances and allow statements (parts, modes, targets, distances with units)
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace cbtl::detail {

// True if `d` is an indexed family (a var, const or observe declaration with an index).
bool isFamily(const Decl* d);

// The index of a var, const or observe declaration (nullptr for other kinds or unindexed ones).
const IndexSpec* indexOf(const Decl* d);

class TypeChecker {
 public:
  TypeChecker(TypeContext& types, const GlobalSymbols& symbols, DiagnosticEngine& diags)
      : types_(types), symbols_(symbols), diags_(diags) {}

  // Checks every module (root first); reports into the diagnostics engine given at construction.
  void run(const std::vector<std::unique_ptr<Module>>& modules);

  // Types `e` (null is an error type) and stores the result in e->type. A bare family name is only
  // allowed with `allowFamily` (the base of an index expression or a sample target).
  const Type* check(Expr* e, bool allowFamily = false);

 private:
  const Type* err() { return types_.error(); }

  // --- TypeChecker.cpp: declaration dispatch ---
  void checkTop(Decl& d);

  // --- TypeCheckerFunctions.cpp: the call graph of user functions ---
  // The user functions `e` calls (extern ones left out), in the order written.
  void collectCalls(const Expr* e, std::vector<const FuncDecl*>& out);
  // E0308 for a function that calls itself, directly or through others; E0319 for one whose inlined
  // expansion is over a limit of CompileLimits (nodes, depth, nested calls). Sets FuncDecl::inlinedNodes of
  // every function that is neither. Runs after every function body is typed.
  void checkFunctions(const std::vector<std::unique_ptr<Module>>& modules);

  // --- TypeCheckerExprs.cpp: expressions ---
  const Type* checkInner(Expr& e, bool allowFamily);
  const Type* paramType(const NameRef& r);
  const Type* nameType(Expr& e, bool allowFamily);
  const Type* memberType(Expr& e);
  const Type* indexType(Expr& e);
  const Type* inType(Expr& e);
  const Type* listType(Expr& e);
  const Type* numericResult(const Type* a, const Type* b);
  const Type* binaryType(Expr& e);
  // The element type of a collection that a binder or index ranges over; `what` names it in errors.
  const Type* elementOf(const Type* collection, const Expr& at, const char* what);
  void bindBinder(Binder& b, const char* what);
  // Types `e` and reports E0301 unless its type is assignable to `want`; returns the type found.
  const Type* expect(Expr* e, const Type* want, const char* context);

  // --- TypeCheckerCalls.cpp: calls ---
  // Matches call arguments to parameters (positional first, then named). Returns false on a mismatch
  // already reported. `order[i]` is the argument for parameter i.
  bool matchArgs(const std::string& what, const std::string& name, const std::vector<Param>& params,
                 std::vector<Arg>& args, SourceRange at, SourceRange declAt, std::vector<Arg*>& order);
  // Checks a call against a callable declaration; returns the (substituted) result type.
  const Type* checkCallable(const CallableDecl& c, std::vector<Arg>& args, SourceRange at);
  const Type* callType(Expr& e);

  // --- TypeCheckerDecls.cpp: declarations ---
  void checkIndex(IndexSpec* index);
  // Constants are checked on first use, so a constant may be used before its declaration.
  const Type* constType(const Expr& use, const ConstDecl& c);
  void checkConst(ConstDecl& c);
  void checkConstValue(ConstDecl& c);
  void checkDomain(VarDecl& v);
  // Checks that the (typed, constant) domain `d` of a variable of type `t` has the form that type needs.
  void checkDomainForm(const Type* t, const Type* dt, const Expr* d);
  // Checks a box(...) domain whose named ranges must be among `names`; false if `d` is not a box(...).
  bool checkBoxDomain(const Type* t, const Expr* d, const std::vector<std::string>& names);
  void checkVar(VarDecl& v);
  const Type* sampleTarget(Expr* t);
  void checkSample(SampleDecl& s);
  void checkScopeStmt(Decl& d);
  void checkItems(ItemsDecl& items);
  void checkRobot(RobotDecl& r);
  void checkPersonal(PersonalDecl& g);

  // --- TypeCheckerTasks.cpp: skills and tasks ---
  void checkSkill(SkillDecl& s);
  void checkActions(std::vector<std::unique_ptr<ActionStmt>>& stmts);
  void checkTask(TaskDecl& t);
  // Checks a skill instance's arguments against its skill's parameters (arity, variables, types).
  void checkSkillArgs(SkillInstance& inst);

  // --- TypeCheckerClearances.cpp: clearances and allow statements ---
  // E0601 unless the length has the unit m, cm or mm; E0602 if it is negative (`touchDepth`: a touch's depth).
  void checkLength(const Length& l, bool touchDepth);
  void checkClearance(ClearanceDecl& c);
  // The part, the mode, the target (a clearance, else text), the distance and a body that is not empty.
  void checkAllow(ActionStmt& s);

  TypeContext& types_;
  const GlobalSymbols& symbols_;
  DiagnosticEngine& diags_;
  bool inDomain_ = false;                             // while typing a variable's domain, where box(...) is allowed
  std::set<FileId> stdFiles_;                         // the standard library's modules (their externs are provided)
  std::set<const CallableDecl*> unprovidedReported_;  // E0318 once per declaration
  std::set<const ConstDecl*> constsInProgress_;
  std::set<const ConstDecl*> constCyclesReported_;
};

}  // namespace cbtl::detail
