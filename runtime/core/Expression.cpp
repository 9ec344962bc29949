#include "runtime/core/Expression.h"

#include <algorithm>
#include <cmath>

namespace cbtl::rt {

namespace {
const CallContext kNoCall{};
}  // namespace

namespace {
// Values are a handful of doubles: a plain loop beats a call to memmove.
inline void copySmall(const double* from, std::size_t n, double* to) {
  for (std::size_t i = 0; i < n; ++i) to[i] = from[i];
}
// Calls with a scalar result whose arguments take at most this many doubles take the direct path.
constexpr std::size_t kMaxScalarArgs = 16;
// Program guarantees no node is wider (Expression.h).
constexpr std::size_t kMaxWidth = kMaxValueWidth;
}  // namespace

// A table entry for a run-time index. Indices come from typed values, but a sampler or an observation can
// hand over anything (NaN, 1e300): clamp into [0, count) rather than read past the table or convert an
// out-of-range double (undefined behaviour). Program never builds an empty table.
inline std::uint32_t tableIndex(double idx, std::uint32_t count) {
  if (!(idx > 0)) return 0;  // negative and NaN
  if (idx >= static_cast<double>(count)) return count - 1;
  return static_cast<std::uint32_t>(idx);
}

// Whether evalScalar computes this node itself (rather than falling back to eval, which would loop).
bool ExprPool::scalarPath(const PackedNode& n) const {
  switch (n.op) {
    case Op::ReadVar:
    case Op::ReadObs:
    case Op::ReadFrame:
    case Op::TableVar:
    case Op::TableObs:
    case Op::TableConst:
    case Op::Not:
    case Op::Neg:
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge:
    case Op::And:
    case Op::Or:
    case Op::Implies:
    case Op::Iff:
    case Op::InRange:
    case Op::If:
      return true;
    case Op::Add:
    case Op::Sub:
    case Op::Mul:
      return nodes_[kid(n, 0)].width == 1 && nodes_[kid(n, 1)].width == 1;
    case Op::Eq:
    case Op::Ne:
    case Op::InSet:
      return nodes_[kid(n, 0)].width == 1;
    case Op::Member: {
      const Op base = nodes_[kid(n, 0)].op;
      return base == Op::ReadVar || base == Op::ReadObs || base == Op::ReadFrame || base == Op::Const;
    }
    case Op::Call: {
      std::size_t width = 0;
      for (std::size_t i = 0; i < n.kidCount; ++i) width += nodes_[kid(n, i)].width;
      return width <= kMaxScalarArgs;
    }
    default:
      return false;
  }
}

double ExprPool::evalScalar(std::uint32_t root, const EvalContext& ctx) const {
  const PackedNode& n = nodes_[root];
  // Children that are plain reads are taken directly: most operands are variables and constants, and a
  // recursive call per leaf dominated the evaluation time.
  auto S = [&](std::size_t i) -> double {
    const std::uint32_t k = kid(n, i);
    const PackedNode& c = nodes_[k];
    if (c.op == Op::ReadVar) return ctx.assignment[c.a];
    if (c.op == Op::Const) return constants_[c.a];
    return evalScalar(k, ctx);
  };
  auto scalarKids = [&]() { return nodes_[kid(n, 0)].width == 1 && nodes_[kid(n, 1)].width == 1; };
  switch (n.op) {
    case Op::Const:
      return constants_[n.a];
    case Op::ReadVar:
      return ctx.assignment[n.a];
    case Op::ReadObs:
      return ctx.observation[n.a];
    case Op::ReadFrame:
      return ctx.frame[n.a];
    case Op::TableVar:
    case Op::TableObs:
    case Op::TableConst: {
      const std::uint32_t i = tableIndex(S(0), n.count);
      const std::uint32_t at = tables_[n.a + i];
      return n.op == Op::TableVar ? ctx.assignment[at] : n.op == Op::TableObs ? ctx.observation[at] : constants_[at];
    }
    case Op::Not:
      return S(0) != 0 ? 0 : 1;
    case Op::Neg:
      return -S(0);
    case Op::Add:
      if (scalarKids()) return S(0) + S(1);
      break;
    case Op::Sub:
      if (scalarKids()) return S(0) - S(1);
      break;
    case Op::Mul:
      if (scalarKids()) return S(0) * S(1);
      break;
    case Op::Eq:
    case Op::Ne:
      if (nodes_[kid(n, 0)].width == 1) {
        const bool eq = S(0) == S(1);
        return eq == (n.op == Op::Eq) ? 1 : 0;
      }
      break;
    case Op::Lt:
      return S(0) < S(1) ? 1 : 0;
    case Op::Le:
      return S(0) <= S(1) ? 1 : 0;
    case Op::Gt:
      return S(0) > S(1) ? 1 : 0;
    case Op::Ge:
      return S(0) >= S(1) ? 1 : 0;
    case Op::And:
      return (S(0) != 0 && S(1) != 0) ? 1 : 0;
    case Op::Or:
      return (S(0) != 0 || S(1) != 0) ? 1 : 0;
    case Op::Implies:
      return (S(0) == 0 || S(1) != 0) ? 1 : 0;
    case Op::Iff:
      return ((S(0) != 0) == (S(1) != 0)) ? 1 : 0;
    case Op::InRange: {
      const double x = S(0);
      return (x >= S(1) && x <= S(2)) ? 1 : 0;
    }
    case Op::If:
      return evalScalar(S(0) != 0 ? kid(n, 1) : kid(n, 2), ctx);
    case Op::InSet:
      if (nodes_[kid(n, 0)].width == 1) {
        const double x = S(0);
        const double* begin = constants_.data() + n.a;
        return std::find(begin, begin + n.b, x) != begin + n.b ? 1 : 0;
      }
      break;
    case Op::Member:
      if (n.width == 1) {
        const PackedNode& base = nodes_[kid(n, 0)];
        switch (base.op) {
          case Op::ReadVar:
            return ctx.assignment[base.a + n.a];
          case Op::ReadObs:
            return ctx.observation[base.a + n.a];
          case Op::ReadFrame:
            return ctx.frame[base.a + n.a];
          case Op::Const:
            return constants_[base.a + n.a];
          default:
            break;
        }
      }
      break;
    case Op::Call:
      if (n.width == 1 && scalarPath(n)) {
        double args[kMaxScalarArgs];
        std::size_t at = 0;
        for (std::size_t i = 0; i < n.kidCount; ++i) {
          const std::uint32_t k = kid(n, i);
          if (nodes_[k].width == 1) {
            args[at++] = S(i);
          } else {
            eval(k, ctx, args + at);
            at += nodes_[k].width;
          }
        }
        double out = 0;
        n.fn(ctx.call != nullptr ? *ctx.call : kNoCall, std::span<const double>(args, at),
             std::span<const std::uint16_t>(kidWidths_.data() + n.kidWidths, n.kidCount), std::span<double>(&out, 1));
        return out;
      }
      break;
    default:
      break;
  }
  double v[kMaxWidth];
  eval(root, ctx, v);
  return v[0];
}

void ExprPool::eval(std::uint32_t root, const EvalContext& ctx, double* out) const {
  const PackedNode& n = nodes_[root];
  if (n.width == 1 && scalarPath(n)) {
    out[0] = evalScalar(root, ctx);
    return;
  }
  switch (n.op) {
    case Op::Const:
      copySmall(constants_.data() + n.a, n.width, out);
      return;
    case Op::ReadVar:
      copySmall(ctx.assignment + n.a, n.width, out);
      return;
    case Op::ReadObs:
      copySmall(ctx.observation + n.a, n.width, out);
      return;
    case Op::ReadFrame:
      copySmall(ctx.frame + n.a, n.width, out);
      return;
    case Op::TableVar:
    case Op::TableObs:
    case Op::TableConst: {
      const std::uint32_t i = tableIndex(evalScalar(kid(n, 0), ctx), n.count);
      const std::uint32_t at = tables_[n.a + i];
      const double* base = n.op == Op::TableVar   ? ctx.assignment
                           : n.op == Op::TableObs ? ctx.observation
                                                  : constants_.data();
      copySmall(base + at, n.width, out);
      return;
    }
    case Op::Member: {
      double v[kMaxWidth];
      eval(kid(n, 0), ctx, v);
      copySmall(v + n.a, n.width, out);
      return;
    }
    case Op::Neg: {
      eval(kid(n, 0), ctx, out);
      for (std::size_t i = 0; i < n.width; ++i) out[i] = -out[i];
      return;
    }
    case Op::Not:
      out[0] = evalBool(kid(n, 0), ctx) ? 0 : 1;
      return;
    case Op::Add:
    case Op::Sub:
    case Op::Mul:
    case Op::Div:
    case Op::Mod:
    case Op::Pow: {
      double x[kMaxWidth], y[kMaxWidth];
      eval(kid(n, 0), ctx, x);
      eval(kid(n, 1), ctx, y);
      const std::size_t wx = nodes_[kid(n, 0)].width, wy = nodes_[kid(n, 1)].width;
      for (std::size_t i = 0; i < n.width; ++i) {
        const double p = x[wx == 1 ? 0 : i], q = y[wy == 1 ? 0 : i];
        switch (n.op) {
          case Op::Add:
            out[i] = p + q;
            break;
          case Op::Sub:
            out[i] = p - q;
            break;
          case Op::Mul:
            out[i] = p * q;
            break;
          case Op::Div:
            out[i] = n.b ? (q == 0 ? 0 : std::trunc(p / q)) : p / q;
            break;  // b: integer division
          case Op::Mod:
            out[i] = q == 0 ? 0 : std::fmod(p, q);
            break;
          default:
            out[i] = std::pow(p, q);
            break;
        }
      }
      return;
    }
    case Op::Eq:
    case Op::Ne: {
      double x[kMaxWidth], y[kMaxWidth];
      eval(kid(n, 0), ctx, x);
      eval(kid(n, 1), ctx, y);
      const std::size_t w = nodes_[kid(n, 0)].width;
      const bool eq = std::equal(x, x + w, y);
      out[0] = (eq == (n.op == Op::Eq)) ? 1 : 0;
      return;
    }
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge: {
      const double x = evalScalar(kid(n, 0), ctx), y = evalScalar(kid(n, 1), ctx);
      const bool r = n.op == Op::Lt ? x < y : n.op == Op::Le ? x <= y : n.op == Op::Gt ? x > y : x >= y;
      out[0] = r ? 1 : 0;
      return;
    }
    case Op::And:
      out[0] = (evalBool(kid(n, 0), ctx) && evalBool(kid(n, 1), ctx)) ? 1 : 0;
      return;
    case Op::Or:
      out[0] = (evalBool(kid(n, 0), ctx) || evalBool(kid(n, 1), ctx)) ? 1 : 0;
      return;
    case Op::Implies:
      out[0] = (!evalBool(kid(n, 0), ctx) || evalBool(kid(n, 1), ctx)) ? 1 : 0;
      return;
    case Op::Iff:
      out[0] = (evalBool(kid(n, 0), ctx) == evalBool(kid(n, 1), ctx)) ? 1 : 0;
      return;
    case Op::InRange: {
      const double x = evalScalar(kid(n, 0), ctx);
      out[0] = (x >= evalScalar(kid(n, 1), ctx) && x <= evalScalar(kid(n, 2), ctx)) ? 1 : 0;
      return;
    }
    case Op::InSet: {
      const double x = evalScalar(kid(n, 0), ctx);
      const double* begin = constants_.data() + n.a;
      out[0] = std::find(begin, begin + n.b, x) != begin + n.b ? 1 : 0;
      return;
    }
    case Op::If:
      eval(evalBool(kid(n, 0), ctx) ? kid(n, 1) : kid(n, 2), ctx, out);
      return;
    case Op::Call: {
      double args[kMaxCallArgsWidth];
      std::size_t at = 0;
      for (std::size_t i = 0; i < n.kidCount; ++i) {
        const std::uint32_t k = kid(n, i);
        eval(k, ctx, args + at);
        at += nodes_[k].width;
      }
      n.fn(ctx.call != nullptr ? *ctx.call : kNoCall, std::span<const double>(args, at),
           std::span<const std::uint16_t>(kidWidths_.data() + n.kidWidths, n.kidCount),
           std::span<double>(out, n.width));
      return;
    }
    case Op::Forall:
    case Op::Exists: {
      // kids: [lo, hi] for ranges (count == 0), then where, body. Enum/item sets: members 0 .. count-1.
      const bool isForall = n.op == Op::Forall;
      double lo = 0, hi = static_cast<double>(n.count) - 1;
      std::size_t k = 0;
      if (n.count == 0) {
        lo = evalScalar(kid(n, 0), ctx);
        hi = evalScalar(kid(n, 1), ctx);
        k = 2;
      }
      const std::uint32_t where = kid(n, k), body = kid(n, k + 1);
      // A range bound read at run time can be anything; a range too long to walk (or with a non-finite
      // bound) makes the quantifier false, which rejects the candidate instead of hanging the solver.
      if (n.count == 0 && lo <= hi && !(hi - lo < static_cast<double>(kMaxQuantifierRange))) {
        out[0] = 0;
        return;
      }
      bool result = isForall;
      for (double v = lo; v <= hi; v += 1) {
        ctx.frame[n.a] = v;
        if (!evalBool(where, ctx)) continue;
        const bool b = evalBool(body, ctx);
        if (isForall && !b) {
          result = false;
          break;
        }
        if (!isForall && b) {
          result = true;
          break;
        }
      }
      out[0] = result ? 1 : 0;
      return;
    }
    case Op::Concat: {
      std::size_t at = 0;
      for (std::size_t i = 0; i < n.kidCount; ++i) {
        const std::uint32_t k = kid(n, i);
        eval(k, ctx, out + at);
        at += nodes_[k].width;
      }
      return;
    }
  }
}

}  // namespace cbtl::rt
