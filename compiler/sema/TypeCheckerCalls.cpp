// check-types: calls. Arguments are matched to parameters (positional, then named) and unified with the
// declared parameter types, so that a generic extern signature (vec<N>, Conf<R>) is instantiated per call.
#include "compiler/sema/TypeCheckerInternal.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

namespace cbtl::detail {

bool TypeChecker::matchArgs(const std::string& what, const std::string& name, const std::vector<Param>& params,
                            std::vector<Arg>& args, SourceRange at, SourceRange declAt, std::vector<Arg*>& order) {
  order.assign(params.size(), nullptr);
  bool ok = true;
  bool sawNamed = false;
  std::size_t positional = 0;
  for (auto& a : args) {
    if (a.name.name.empty()) {
      if (sawNamed) {
        diags_.error("E0307", a.range, "a positional argument cannot follow a named one");
        ok = false;
        continue;
      }
      if (positional >= params.size()) {
        diags_
            .error("E0302", a.range,
                   fmt::format("{} '{}' takes {} argument{}, but {} were given", what, name, params.size(),
                               params.size() == 1 ? "" : "s", args.size()))
            .note("declared here", declAt);
        return false;
      }
      order[positional++] = &a;
      continue;
    }
    sawNamed = true;
    std::size_t i = 0;
    for (; i < params.size(); ++i) {
      if (params[i].name.name == a.name.name) break;
    }
    if (i == params.size()) {
      std::vector<std::string> names;
      for (const auto& p : params) names.push_back(p.name.name);
      Diagnostic& d = diags_.error("E0307", a.name.range,
                                   fmt::format("{} '{}' has no parameter named '{}'", what, name, a.name.name));
      const std::string guess = closestMatch(a.name.name, names);
      if (!guess.empty()) d.help(fmt::format("did you mean '{}'?", guess));
      ok = false;
      continue;
    }
    if (order[i] != nullptr) {
      diags_.error("E0307", a.name.range, fmt::format("argument '{}' is given twice", a.name.name));
      ok = false;
      continue;
    }
    order[i] = &a;
  }
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (order[i] == nullptr && ok) {
      diags_
          .error("E0302", at,
                 fmt::format("{} '{}' takes {} argument{}; '{}' is missing", what, name, params.size(),
                             params.size() == 1 ? "" : "s", params[i].name.name))
          .note("declared here", declAt);
      return false;
    }
  }
  return ok;
}

const Type* TypeChecker::checkCallable(const CallableDecl& c, std::vector<Arg>& args, SourceRange at) {
  // cbtl's runtime implements exactly the standard library's extern functions and samplers; any other extern
  // would be refused when the program is loaded for running, so it is refused here, at its first use.
  if (c.isExtern && (c.kind == DeclKind::Function || c.kind == DeclKind::Sampler) &&
      stdFiles_.count(c.name.range.file) == 0 && unprovidedReported_.insert(&c).second) {
    diags_
        .error("E0318", at,
               fmt::format("cbtl's runtime provides no extern {} '{}': only the standard library's externs have "
                           "implementations",
                           c.kind == DeclKind::Function ? "function" : "sampler", c.name.name))
        .note("declared here", c.name.range)
        .help(c.kind == DeclKind::Function
                  ? "write it in the language, `fn name(x: real) -> real = ...;`, or use a std module's function"
                  : "draw with 'uniform' or a std sampler (uniformReal, uniformInt, bernoulli, ...)");
  }
  std::vector<Arg*> order;
  for (auto& a : args) check(a.value.get());
  if (!matchArgs(toString(c.kind), c.name.name, c.params, args, at, c.name.range, order)) return err();
  Unifier unifier(types_);
  bool ok = true;
  for (std::size_t i = 0; i < c.params.size(); ++i) {
    const Type* formal = c.params[i].type.resolved;
    const Type* actual = order[i]->value->type;
    if (formal == nullptr || actual == nullptr) continue;
    if (!unifier.unify(formal, actual)) {
      diags_
          .error("E0301", order[i]->value->range,
                 fmt::format("argument '{}' of '{}' must be {}, but this is {}", c.params[i].name.name, c.name.name,
                             unifier.substitute(formal)->spelling, actual->spelling))
          .note("declared here", c.params[i].name.range);
      ok = false;
    }
  }
  if (!ok) return err();
  if (!c.result || !c.result->resolved) return types_.voidType();
  const Type* result = unifier.substitute(c.result->resolved);
  if (result->isGeneric()) {
    diags_.error("E0301", at,
                 fmt::format("cannot infer the result type {} of '{}' from its arguments", c.result->resolved->spelling,
                             c.name.name));
    return err();
  }
  return result;
}

const Type* TypeChecker::callType(Expr& e) {
  Expr* callee = e.operands[0].get();
  if (callee->kind != ExprKind::Name) {
    diags_.error("E0313", callee->range, "only named functions can be called");
    for (auto& a : e.args) check(a.value.get());
    return err();
  }
  const NameRef& r = callee->ref;
  if (r.kind == RefKind::Unresolved) {
    for (auto& a : e.args) check(a.value.get());
    return err();
  }
  if (r.kind == RefKind::Function) return checkCallable(static_cast<const CallableDecl&>(*r.decl), e.args, e.range);
  if (r.kind == RefKind::Builtin && r.index == static_cast<int>(BuiltinId::Box)) {
    if (!inDomain_) {
      diags_.error("E0313", callee->range, "box(...) describes a domain; use it after 'in' in a variable declaration");
    }
    for (auto& a : e.args) check(a.value.get());
    return types_.voidType();
  }
  for (auto& a : e.args) check(a.value.get());
  const char* hint = r.kind == RefKind::Sampler  ? "samplers are used in 'sample x ~ name(...);'"
                     : r.kind == RefKind::Action ? "actions are called in a skill's 'do' block"
                                                 : "only functions can be called in expressions";
  diags_.error("E0313", callee->range, fmt::format("'{}' cannot be called here", callee->text)).help(hint);
  return err();
}

}  // namespace cbtl::detail
