// NameResolverInternal.h — the `resolve-names` pass's resolver, shared by its implementation files only.
//
// Internal to compiler/sema: callers use resolveNames() (NameResolver.h). The resolver is one class
// because every concern reads and writes the same state (the global symbol table, the stack of local
// scopes, the type parameters of the signature being resolved) and they call each other (declarations
// resolve types and expressions, expressions open scopes for their binders). Its member functions are
// implemented by concern:
//   NameResolver.cpp       the entry point, pass 1 (declare every top-level name) and the pass-2 dispatch
//   NameResolverScopes.cpp local scopes and name lookup (with did-you-mean suggestions)
//   NameResolverTypes.cpp  types as written to semantic types
//   NameResolverExprs.cpp  names in expressions (qualified enum members and item entries, calls, binders)
//   NameResolverDecls.cpp  scope statements, callables, generators, skills, actions and tasks
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/sema/Type.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::detail {

class NameResolver {
 public:
  NameResolver(TypeContext& types, GlobalSymbols& symbols, DiagnosticEngine& diags)
      : types_(types), symbols_(symbols), diags_(diags) {}

  // Declares the names of every module (the first is the root file), then resolves each module.
  void run(const std::vector<std::unique_ptr<Module>>& modules);

 private:
  struct Scope {
    std::map<std::string, Symbol> names;
  };

  // --- NameResolver.cpp: pass 1 and the pass-2 dispatch ---
  void duplicate(const Ident& name, SourceRange previous);
  bool claim(const Ident& name);
  void declare(Module& module, bool isRoot);
  void resolveModule(Module& module);

  // --- NameResolverScopes.cpp: scopes and lookup ---
  void push() { scopes_.emplace_back(); }
  void pop() { scopes_.pop_back(); }
  // Binds `name` in the innermost scope; a second binding of the same name there is E0202.
  void bindLocal(const Ident& name, Symbol sym);
  std::vector<std::string> visibleNames() const;
  // Looks a name up; returns Unresolved (and reports, with `report`) if it is unknown.
  NameRef lookup(const std::string& name, SourceRange at, bool report = true);
  NameRef lookupWithBinders(const std::string& name, SourceRange at, bool report = true);
  void unknownName(const std::string& name, SourceRange at);
  static NameRef toRef(const Symbol& s);

  // --- NameResolverTypes.cpp: types ---
  // Resolves `t` (and its arguments) and stores the result in t.resolved; unknown types are errors.
  const Type* resolveType(TypeRef& t);
  bool isTypeParam(const std::string& name) const;
  const Type* resolveTypeInner(TypeRef& t);
  // E0309 unless builtin type `t` is written without arguments.
  void checkNoTypeArgs(const TypeRef& t);
  // The one argument of builtin type `t` (vec, Conf, set); null after reporting E0309 if there is not one.
  TypeRef::Arg* singleTypeArg(TypeRef& t);
  const Type* vecType(TypeRef& t);
  const Type* confType(TypeRef& t);
  const Type* setType(TypeRef& t);
  const Type* unknownType(TypeRef& t);

  // --- NameResolverExprs.cpp: expressions ---
  void resolveArgs(std::vector<Arg>& args);
  // Resolves the binder's set, then binds its names in the current (caller-pushed) scope.
  void resolveBinder(Binder& b);
  void resolveExpr(Expr* e);
  void resolveMember(Expr* e);

  // --- NameResolverDecls.cpp: declarations ---
  void resolveIndex(IndexSpec* index);
  void resolveScopeStmt(Decl& d);
  void bindBodyVariables(const std::vector<std::unique_ptr<Decl>>& body);
  void resolveActions(std::vector<std::unique_ptr<ActionStmt>>& stmts);
  void resolveAllowTarget(AllowClause& a);
  void resolveCallable(CallableDecl& c);
  void resolvePersonal(PersonalDecl& g);
  void resolveModelArgs(ModelFactor& f);
  void resolveLearnRule(LearnRule& rule);
  void resolveSkill(SkillDecl& s);
  void resolveTask(TaskDecl& t);

  TypeContext& types_;
  GlobalSymbols& symbols_;
  DiagnosticEngine& diags_;
  std::map<std::string, SourceRange> claimed_;  // every top-level name, where it was first declared
  std::vector<Scope> scopes_;                   // innermost last
  std::vector<std::string> typeParams_;         // of the extern signature being resolved
};

}  // namespace cbtl::detail
