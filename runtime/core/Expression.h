// Expression.h — compiled expressions: a flat pool of nodes evaluated by a switch, with no allocation and
// no name look-up per evaluation.
//
// A node writes `width` doubles (its value in the Values.h layout) to the output it is handed. Children are
// node indices into the same pool. Reads come from the EvalContext: the assignment (CSP variables), the
// observation vector, and the frame (parameters bound from an event, binder values of quantifiers and
// loops). Scalars that are compile-time constant are folded into Const nodes.
#pragma once

#include "runtime/core/Builtins.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace cbtl::rt {

// Limits the evaluator's stack buffers rely on. Program rejects, at load and with the source location, any
// expression whose value is wider than kMaxValueWidth doubles or any call whose arguments take more than
// kMaxCallArgsWidth doubles, so no fixed-size buffer is ever indexed past its end by program data.
inline constexpr std::size_t kMaxValueWidth = 64;
inline constexpr std::size_t kMaxCallArgsWidth = 4 * kMaxValueWidth;
// An integer-range quantifier whose run-time bounds span more members than this (or are not finite) is
// false: a candidate that would take that long to check is rejected rather than hanging the solver.
inline constexpr std::size_t kMaxQuantifierRange = std::size_t{1} << 20;

enum class Op : std::uint8_t {
  Const,       // pool constants [a, a + width)
  ReadVar,     // assignment[a .. a + width)
  ReadObs,     // observation[a .. a + width)
  ReadFrame,   // frame[a .. a + width)
  TableVar,    // assignment[table[a + idx]]: child 0 = index (0-based member index)
  TableObs,    // observation[table[a + idx]]
  TableConst,  // constants[table[a + idx]]
  Member,      // child 0's component a .. a + width
  Neg,
  Not,
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Pow,  // component-wise; a scalar operand broadcasts
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
  InRange,  // child 0 in [child 1, child 2]
  InSet,    // child 0 (scalar) in constants[a .. a + b)
  If,       // child 0 ? child 1 : child 2
  Call,     // fn(children...)
  Forall,
  Exists,  // binder frame slot a; members: constants[b .. b + count) or range children; see eval
  Concat,  // children laid end to end (vec literals of tuples)
};

struct Node {
  Op op = Op::Const;
  std::uint16_t width = 1;
  std::uint32_t a = 0, b = 0, count = 0;
  FunctionImpl fn = nullptr;
  std::vector<std::uint32_t> kids;
  std::vector<std::uint16_t> kidWidths;  // Call: argument widths
};

// The form the evaluator reads: fixed size, children in one shared array (better locality than a vector
// per node).
struct PackedNode {
  Op op = Op::Const;
  std::uint16_t width = 1;
  std::uint16_t kidCount = 0;
  std::uint32_t a = 0, b = 0, count = 0;
  std::uint32_t kids = 0;       // first child in ExprPool's child array
  std::uint32_t kidWidths = 0;  // Call: first argument width in ExprPool's width array
  FunctionImpl fn = nullptr;
};

struct EvalContext {
  const double* assignment = nullptr;
  const double* observation = nullptr;
  double* frame = nullptr;
  const CallContext* call = nullptr;  // handed to built-ins; null: an empty context
};

class ExprPool {
 public:
  std::uint32_t add(const Node& n) {
    PackedNode p;
    p.op = n.op;
    p.width = n.width;
    p.kidCount = static_cast<std::uint16_t>(n.kids.size());
    p.a = n.a;
    p.b = n.b;
    p.count = n.count;
    p.fn = n.fn;
    p.kids = static_cast<std::uint32_t>(kids_.size());
    kids_.insert(kids_.end(), n.kids.begin(), n.kids.end());
    p.kidWidths = static_cast<std::uint32_t>(kidWidths_.size());
    kidWidths_.insert(kidWidths_.end(), n.kidWidths.begin(), n.kidWidths.end());
    nodes_.push_back(p);
    return static_cast<std::uint32_t>(nodes_.size() - 1);
  }
  std::uint32_t addConstants(std::span<const double> values) {
    const auto at = static_cast<std::uint32_t>(constants_.size());
    constants_.insert(constants_.end(), values.begin(), values.end());
    return at;
  }
  std::uint32_t addTable(std::span<const std::uint32_t> offsets) {
    const auto at = static_cast<std::uint32_t>(tables_.size());
    tables_.insert(tables_.end(), offsets.begin(), offsets.end());
    return at;
  }
  std::uint16_t width(std::uint32_t i) const { return nodes_[i].width; }
  const PackedNode& node(std::uint32_t i) const { return nodes_[i]; }
  std::size_t size() const { return nodes_.size(); }

  // Evaluates node `root` into out[0 .. width). Preconditions: out has room for the node's width; the context's
  // frame has at least Program::frameSize() slots.
  void eval(std::uint32_t root, const EvalContext& ctx, double* out) const;
  // The first component of a node's value; width-1 nodes (almost all of them) take a direct path with no
  // output buffers.
  double evalScalar(std::uint32_t root, const EvalContext& ctx) const;
  bool evalBool(std::uint32_t root, const EvalContext& ctx) const { return evalScalar(root, ctx) != 0; }

  // Whether node `root` or any node below it calls a built-in for which `pred` is true.
  template <class Pred>
  bool callsAny(std::uint32_t root, const Pred& pred) const {
    const PackedNode& n = nodes_[root];
    if (n.op == Op::Call && pred(n.fn)) return true;
    for (std::size_t i = 0; i < n.kidCount; ++i)
      if (callsAny(kid(n, i), pred)) return true;
    return false;
  }

 private:
  bool scalarPath(const PackedNode& n) const;
  std::uint32_t kid(const PackedNode& n, std::size_t i) const { return kids_[n.kids + i]; }
  std::vector<PackedNode> nodes_;
  std::vector<std::uint32_t> kids_;
  std::vector<std::uint16_t> kidWidths_;
  std::vector<double> constants_;
  std::vector<std::uint32_t> tables_;
};

}  // namespace cbtl::rt
