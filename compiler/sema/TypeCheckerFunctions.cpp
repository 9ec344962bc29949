// check-types: the call graph of user functions. Recursion (E0308) and how far a function expands when the
// runtime inlines its calls (E0319), both found in one depth-first walk over the call graph.
//
// The walk keeps its own stack instead of recursing, so that a chain of 100,000 functions each calling the
// next (a few MB of source) cannot exhaust the compiler's stack; the measures of a function are computed once,
// when all its callees are done, so the walk is linear in the size of the program even when the expansion it
// measures is exponential.
#include "compiler/driver/CompileLimits.h"
#include "compiler/sema/TypeCheckerInternal.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace cbtl::detail {
namespace {

// What the runtime builds for an expression once every call of a user function in it is inlined.
struct Expansion {
  std::size_t nodes = 0;      // expression nodes
  std::size_t depth = 0;      // levels
  std::size_t callDepth = 0;  // calls nested through function bodies
  bool unknown = false;       // reaches a function that is recursive or already over a limit: not measured
  // The call that contributes the most nodes, and the one through which calls nest deepest (notes).
  const Expr* largestCall = nullptr;
  std::size_t largestCallNodes = 0;
  const Expr* deepestCall = nullptr;
};

const FuncDecl* userCallee(const Expr& e) {
  if (e.kind != ExprKind::Call || e.ref.kind != RefKind::Function) return nullptr;
  const auto* f = static_cast<const FuncDecl*>(e.ref.decl);
  return f->isExtern || !f->body ? nullptr : f;
}

// Measures `e` with the measures of the functions it calls, which `done` must hold (a callee missing from it
// makes the result unknown). Recursive over the expression tree only, whose depth the parser bounds.
Expansion measure(const Expr* e, const std::map<const FuncDecl*, Expansion>& done) {
  Expansion out;
  if (e == nullptr) return out;
  std::size_t childDepth = 0;
  auto add = [&](const Expr* child) {
    const Expansion c = measure(child, done);
    out.nodes += c.nodes;
    childDepth = std::max(childDepth, c.depth);
    if (c.callDepth > out.callDepth) {
      out.callDepth = c.callDepth;
      out.deepestCall = c.deepestCall;
    }
    if (c.largestCallNodes > out.largestCallNodes) {
      out.largestCallNodes = c.largestCallNodes;
      out.largestCall = c.largestCall;
    }
    out.unknown = out.unknown || c.unknown;
  };
  // A call's callee name (operands[0]) is not an expression node of its own in the graph.
  if (e->kind != ExprKind::Call) {
    for (const auto& op : e->operands) add(op.get());
  }
  for (const auto& a : e->args) add(a.value.get());
  if (e->binder) add(e->binder->set.get());
  out.nodes += 1;
  out.depth = childDepth + 1;
  if (const FuncDecl* callee = userCallee(*e)) {
    const auto it = done.find(callee);
    if (it == done.end() || it->second.unknown) {
      out.unknown = true;
      return out;
    }
    // The body replaces the call; its parameters read the argument nodes, so the arguments' depth adds to the
    // body's along a path through a parameter.
    const Expansion& body = it->second;
    out.nodes += body.nodes;
    out.depth = childDepth + body.depth;
    if (body.nodes > out.largestCallNodes) {
      out.largestCallNodes = body.nodes;
      out.largestCall = e;
    }
    if (body.callDepth + 1 > out.callDepth) {
      out.callDepth = body.callDepth + 1;
      out.deepestCall = e;
    }
  }
  return out;
}

// E0319 at the function if its expansion is over a limit; the expansion then counts as unknown, so that the
// functions calling it are not reported again.
Expansion checkExpansion(DiagnosticEngine& diags, const FuncDecl& f, Expansion e);

}  // namespace

void TypeChecker::collectCalls(const Expr* e, std::vector<const FuncDecl*>& out) {
  if (e == nullptr) return;
  if (e->kind == ExprKind::Call && e->ref.kind == RefKind::Function) {
    const auto* f = static_cast<const FuncDecl*>(e->ref.decl);
    if (!f->isExtern) out.push_back(f);
  }
  for (const auto& op : e->operands) collectCalls(op.get(), out);
  for (const auto& a : e->args) collectCalls(a.value.get(), out);
  if (e->binder) collectCalls(e->binder->set.get(), out);
}

void TypeChecker::checkFunctions(const std::vector<std::unique_ptr<Module>>& modules) {
  // Depth-first search; a callee found on the stack closes a cycle, reported once at its caller. A function
  // is measured when it leaves the stack.
  struct Frame {
    const FuncDecl* f;
    std::vector<const FuncDecl*> callees;
    std::size_t next = 0;
    bool recursive = false;
  };
  std::map<const FuncDecl*, int> state;  // 0 unvisited, 1 on the stack, 2 done
  std::map<const FuncDecl*, Expansion> measured;
  std::vector<Frame> stack;
  auto enter = [&](const FuncDecl* f) {
    state[f] = 1;
    Frame frame{f, {}};
    collectCalls(f->body.get(), frame.callees);
    stack.push_back(std::move(frame));
  };
  for (const auto& m : modules) {
    for (const auto& d : m->decls) {
      if (d->kind != DeclKind::Function) continue;  // only then is the downcast valid
      const auto* root = static_cast<const FuncDecl*>(d.get());
      if (root->isExtern || state[root] != 0) continue;
      enter(root);
      while (!stack.empty()) {
        Frame& top = stack.back();
        if (!top.recursive && top.next < top.callees.size()) {
          const FuncDecl* c = top.callees[top.next++];
          if (state[c] == 1) {
            diags_.error("E0308", top.f->name.range, fmt::format("function '{}' is recursive", top.f->name.name))
                .note(fmt::format("it calls '{}'", c->name.name), c->name.range);
            top.recursive = true;
          } else if (state[c] == 0) {
            enter(c);
          }
          continue;
        }
        Expansion e;
        e.unknown = top.recursive;
        if (!top.recursive) e = checkExpansion(diags_, *top.f, measure(top.f->body.get(), measured));
        measured[top.f] = e;
        state[top.f] = 2;
        stack.pop_back();
      }
    }
  }
  // Lowering counts each call with its inlined body in the graph's size (CompileLimits::kMaxGraphSize).
  for (const auto& m : modules) {
    for (const auto& d : m->decls) {
      if (d->kind != DeclKind::Function) continue;
      auto* f = static_cast<FuncDecl*>(d.get());
      const auto it = measured.find(f);
      if (it != measured.end() && !it->second.unknown) f->inlinedNodes = it->second.nodes;
    }
  }
}

namespace {

Expansion checkExpansion(DiagnosticEngine& diags, const FuncDecl& f, Expansion e) {
  if (e.unknown) return e;
  const std::string& name = f.name.name;
  const char* help =
      "the runtime inlines every call of a user function, so a function that calls another twice doubles its "
      "size: call it once and reuse the result (a parameter, a constant or a variable), or write the expression "
      "without the nested calls";
  // A call of f inlines f itself and then the calls nested in its body: the runtime's count is one more.
  if (e.callDepth + 1 > CompileLimits::kMaxCallDepth) {
    diags
        .error("E0319", f.name.range,
               fmt::format("a call of function '{}' inlines {} nested calls, more than the limit of {}", name,
                           e.callDepth + 1, CompileLimits::kMaxCallDepth))
        .note("the deepest chain starts with this call", e.deepestCall->range)
        .help("call fewer functions inside each other; the runtime refuses a deeper expansion");
  } else if (e.nodes > CompileLimits::kMaxInlinedNodes) {
    Diagnostic& d =
        diags.error("E0319", f.name.range,
                    fmt::format("function '{}' expands into {} expression nodes when its calls are inlined, more than "
                                "the limit of {}",
                                name, e.nodes, CompileLimits::kMaxInlinedNodes));
    if (e.largestCall != nullptr)
      d.note(fmt::format("this call alone expands into {} nodes", e.largestCallNodes), e.largestCall->range);
    d.help(help);
  } else if (e.depth > CompileLimits::kMaxInlinedDepth) {
    diags
        .error("E0319", f.name.range,
               fmt::format("function '{}' is {} levels deep when its calls are inlined, more than the limit of {}",
                           name, e.depth, CompileLimits::kMaxInlinedDepth))
        .help(fmt::format("the runtime compiles and evaluates expressions recursively: what it sees after inlining "
                          "may be at most {} levels deep, like a written expression; split the body into "
                          "functions that are not called inside each other's arguments",
                          CompileLimits::kMaxInlinedDepth));
  } else {
    return e;
  }
  e.unknown = true;
  return e;
}

}  // namespace
}  // namespace cbtl::detail
