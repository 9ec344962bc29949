#include "runtime/solver/Solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "runtime/model/Entropy.h"

namespace cbtl::solver {

const char* toString(SolveOutcome o) {
  switch (o) {
    case SolveOutcome::Solved:
      return "Solved";
    case SolveOutcome::InfeasibleWithinBudget:
      return "InfeasibleWithinBudget";
    case SolveOutcome::SamplersStuck:
      return "SamplersStuck";
    case SolveOutcome::NoSamplers:
      return "NoSamplers";
  }
  return "?";
}

std::size_t Solver::memoryEntries() const {
  std::size_t n = 0;
  for (const auto& [k, m] : memory_) n += m.size();
  return n;
}

namespace {

constexpr double kMaxExactInt = 9007199254740992.0;  // 2^53

inline double* copySmall(const double* from, std::size_t n, double* to) {
  for (std::size_t i = 0; i < n; ++i) to[i] = from[i];
  return to + n;
}

// Lists of lists in two flat arrays (compressed rows): the solve loop walks them for every move.
struct Rows {
  std::vector<std::uint32_t> start{0}, items;
  void endRow() { start.push_back(static_cast<std::uint32_t>(items.size())); }
  const std::uint32_t* begin(std::size_t r) const { return items.data() + start[r]; }
  const std::uint32_t* end(std::size_t r) const { return items.data() + start[r + 1]; }
  std::size_t size(std::size_t r) const { return start[r + 1] - start[r]; }
};

// Inverts rows over [0, n): for every item, the rows that contain it.
Rows invert(const Rows& rows, std::size_t rowCount, std::size_t n) {
  std::vector<std::vector<std::uint32_t>> lists(n);
  for (std::size_t r = 0; r < rowCount; ++r) {
    for (const auto* it = rows.begin(r); it != rows.end(r); ++it) lists[*it].push_back(static_cast<std::uint32_t>(r));
  }
  Rows out;
  for (const auto& l : lists) {
    out.items.insert(out.items.end(), l.begin(), l.end());
    out.endRow();
  }
  return out;
}

}  // namespace

SolveResult Solver::solve(const Csp& csp) {
  const rt::Program& program = *csp.program;
  const rt::ExprPool& pool = program.pool();
  const auto& graph = program.graph();
  PersonalEvaluator personal(program, *csp.instances, *csp.user);

  std::vector<double> x = csp.initial;
  std::vector<double> frame(std::max<std::size_t>(program.frameSize(), 1), 0.0);
  rt::EvalContext ctx{x.data(), csp.observation.data(), frame.data(), program.callContext()};

  // Per constraint: the variables it reads, and the positions in the assignment of their values (the
  // sub-assignment its memory stores). Per variable: the constraints and entropy terms that read it.
  const std::size_t nc = csp.constraints.size();
  Rows edgeVars, edgeSlots;
  for (std::size_t i = 0; i < nc; ++i) {
    const auto& ref = csp.constraints[i];
    const auto& vars = ref.personal ? (*csp.instances)[ref.index].hyperedge : graph.constraints[ref.index].vars;
    for (ir::VarId v : vars) {
      edgeVars.items.push_back(v);
      const auto& slot = program.slot(v);
      for (std::uint32_t w = 0; w < slot.type.width; ++w) edgeSlots.items.push_back(slot.offset + w);
    }
    edgeVars.endRow();
    edgeSlots.endRow();
  }
  const Rows readersOf = invert(edgeVars, nc, graph.variables.size());
  const std::size_t ni = csp.instances->size();
  Rows termVars;
  for (std::size_t t = 0; t < ni; ++t) {
    if (std::find(csp.entropyTerms.begin(), csp.entropyTerms.end(), t) != csp.entropyTerms.end()) {
      for (ir::VarId v : (*csp.instances)[t].hyperedge) termVars.items.push_back(v);
    }
    termVars.endRow();
  }
  const Rows termsOf = invert(termVars, ni, graph.variables.size());

  enum : std::uint8_t { Dirty, Holds, Fails };
  std::vector<std::uint8_t> state(nc, Dirty);
  std::vector<std::uint8_t> termDirty(ni, 1);
  std::vector<PersonalValue> termValue(ni);

  SolveResult result;
  result.constraints.resize(nc);
  for (std::size_t i = 0; i < nc; ++i) result.constraints[i].ref = csp.constraints[i];

  // Memory samplers: one per constraint that already has memory when the solve starts.
  std::vector<std::uint32_t> memorySamplers;
  std::vector<Memory*> memories(nc, nullptr);
  if (options_.useMemory) {
    for (std::size_t i = 0; i < nc; ++i) {
      Memory& m = memory_[csp.constraints[i].identity];
      if (m.capacity == 0 || m.width != edgeSlots.size(i)) {
        m = Memory{};
        m.width = edgeSlots.size(i);
        m.capacity = std::max<std::size_t>(options_.memorySize, 1);
        m.ring.assign(m.width * m.capacity, 0.0);
      }
      memories[i] = &m;
      if (!m.empty()) memorySamplers.push_back(static_cast<std::uint32_t>(i));
    }
  }
  const std::size_t userSamplers = csp.samplers.size();
  std::vector<std::uint32_t> order(userSamplers + memorySamplers.size()), swaps(order.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;

  auto remember = [&](std::size_t i) {
    if (memories[i] == nullptr) return;
    double* slot = memories[i]->pushSlot();
    for (const auto* at = edgeSlots.begin(i); at != edgeSlots.end(i); ++at) *slot++ = x[*at];
  };

  auto check = [&](std::size_t i) -> bool {
    if (state[i] != Dirty) return state[i] == Holds;
    const auto& ref = csp.constraints[i];
    ++result.constraints[i].evaluations;
    bool ok;
    if (ref.personal) {
      const PersonalValue v = personal.evaluate(ref.index, ctx);
      ok = personal.holds(ref.index, v);
    } else {
      ok = pool.evalBool(program.constraints()[ref.index].root, ctx);
    }
    state[i] = ok ? Holds : Fails;
    if (ok && options_.memoryPolicy == MemoryPolicy::EverySatisfiedCheck) remember(i);
    return ok;
  };

  auto costOf = [&]() -> double {
    if (csp.cost == CostKind::Entropy) {
      double sum = 0;
      std::size_t active = 0;
      for (std::uint32_t t : csp.entropyTerms) {
        if (termDirty[t]) {
          termValue[t] = personal.evaluate(t, ctx);
          termDirty[t] = 0;
        }
        if (!termValue[t].applies) continue;
        sum += model::bernoulliEntropyBits(termValue[t].probability);
        ++active;
      }
      return active == 0 ? 1.0 : 1.0 - sum / static_cast<double>(active);
    }
    if (csp.cost == CostKind::Declared) {
      double sum = 0;
      for (std::uint32_t c : csp.task->costs) sum += pool.evalScalar(program.costs()[c], ctx);
      return sum;
    }
    return 0;
  };

  auto markWritten = [&](ir::VarId v) {
    for (const auto* c = readersOf.begin(v); c != readersOf.end(v); ++c) state[*c] = Dirty;
    for (const auto* t = termsOf.begin(v); t != termsOf.end(v); ++t) termDirty[*t] = 1;
  };

  // Sized from the program: a family of any size can be drawn by one sampler.
  std::vector<double> scratchBuffer(std::max<std::size_t>(program.maxSamplerOutWidth(), 1));
  std::vector<double> argsBuffer(std::max<std::size_t>(program.maxSamplerArgsWidth(), 1));
  double* const scratch = scratchBuffer.data();
  // Writes a sampler's drawn values (laid out variable after variable in `scratch`) into the candidate.
  auto writeDrawn = [&](const std::vector<ir::VarId>& writes) {
    std::size_t from = 0;
    for (ir::VarId v : writes) {
      const auto& slot = program.slot(v);
      copySmall(scratch + from, slot.type.width, x.data() + slot.offset);
      from += slot.type.width;
      markWritten(v);
    }
  };
  auto runSampler = [&](std::uint32_t s) -> bool {
    const rt::CompiledSampler& cs = program.samplers()[s];
    if (cs.impl != nullptr) {
      double* const args = argsBuffer.data();
      std::size_t at = 0;
      for (std::uint32_t a : cs.args) {
        pool.eval(a, ctx, args + at);
        at += pool.width(a);
      }
      if (!cs.impl(*program.callContext(), std::span<const double>(args, at),
                   std::span<const std::uint16_t>(cs.argWidths), rng_, std::span<double>(scratch, cs.outWidth))) {
        return false;
      }
      writeDrawn(cs.writes);
      return true;
    }
    // `uniform`: draw every component first, so a failure leaves the assignment untouched.
    std::size_t at = 0;
    for (std::size_t k = 0; k < cs.writes.size(); ++k) {
      const auto& plan = cs.uniform[k];
      const auto& slot = program.slot(cs.writes[k]);
      for (std::size_t c = 0; c < slot.type.width; ++c, ++at) {
        switch (plan.kind) {
          case rt::UniformPlan::Kind::Bool:
            scratch[at] = rng_.coin() ? 1 : 0;
            break;
          case rt::UniformPlan::Kind::Choice:
            scratch[at] = plan.choices[rng_.index(plan.choices.size())];
            break;
          case rt::UniformPlan::Kind::Int: {
            // Bounds are clamped to the integers a double holds exactly (and int64 can convert).
            const double lo = std::max(std::ceil(pool.evalScalar(plan.lo[c], ctx)), -kMaxExactInt);
            const double hi = std::min(std::floor(pool.evalScalar(plan.hi[c], ctx)), kMaxExactInt);
            if (!(lo <= hi)) return false;
            scratch[at] =
                static_cast<double>(rng_.uniformInt(static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi)));
            break;
          }
          case rt::UniformPlan::Kind::Real: {
            const double lo = pool.evalScalar(plan.lo[c], ctx), hi = pool.evalScalar(plan.hi[c], ctx);
            if (!(lo <= hi) || !std::isfinite(hi - lo)) return false;
            scratch[at] = rng_.uniform(lo, hi);
            break;
          }
        }
      }
    }
    writeDrawn(cs.writes);
    return true;
  };

  auto runMemorySampler = [&](std::uint32_t i) -> bool {
    const Memory& m = *memories[i];
    if (m.empty()) return false;
    const double* sub = m.at(rng_.index(m.size()));
    for (const auto* at = edgeSlots.begin(i); at != edgeSlots.end(i); ++at) x[*at] = *sub++;
    for (const auto* v = edgeVars.begin(i); v != edgeVars.end(i); ++v) markWritten(*v);
    return true;
  };

  bool found = false;
  double bestCost = std::numeric_limits<double>::infinity();
  std::vector<double> best;
  std::uint64_t attempts = 0;
  for (std::uint64_t iter = 0; iter < options_.maxIters; ++iter) {
    if (found && (attempts >= options_.maxImprovementAttempts || result.improvements >= options_.numImprovements))
      break;
    if (found) ++attempts;
    ++result.iterations;
    bool prune = false;
    double cost = 0;
    if (csp.cost != CostKind::None) {
      cost = costOf();
      prune = cost > bestCost;
    }
    if (prune) {
      ++result.prunedByCost;
    } else {
      ++result.candidatesChecked;
      bool ok = true;
      for (std::size_t i = 0; i < nc; ++i) {
        if (!check(i)) {
          ++result.constraints[i].rejections;
          ok = false;
          break;
        }
      }
      if (ok) {
        if (options_.memoryPolicy == MemoryPolicy::Solutions) {
          for (std::size_t i = 0; i < nc; ++i) remember(i);
        }
        if (found) ++result.improvements;
        found = true;
        if (csp.cost == CostKind::None) {
          result.outcome = SolveOutcome::Solved;
          result.assignment = x;
          result.cost = 0;
          return result;
        }
        best = x;
        bestCost = cost;
      }
    }
    // Move.
    if (order.empty()) {
      result.outcome = found ? SolveOutcome::Solved : SolveOutcome::NoSamplers;
      break;
    }
    // A uniformly random order, drawn lazily (Fisher-Yates one position at a time): the first sampler
    // usually succeeds, so most moves cost one draw instead of a full shuffle. `order` starts every move as
    // the identity; the swaps are undone afterwards instead of rewriting the whole array.
    bool moved = false;
    std::size_t pos = 0;
    for (; pos < order.size() && !moved; ++pos) {
      swaps[pos] = static_cast<std::uint32_t>(pos + rng_.index(order.size() - pos));
      std::swap(order[pos], order[swaps[pos]]);
      const std::uint32_t k = order[pos];
      moved = k < userSamplers ? runSampler(csp.samplers[k]) : runMemorySampler(memorySamplers[k - userSamplers]);
    }
    while (pos-- > 0) std::swap(order[pos], order[swaps[pos]]);
    if (!moved) {
      result.outcome = found ? SolveOutcome::Solved : SolveOutcome::SamplersStuck;
      break;
    }
  }
  if (found) {
    result.outcome = SolveOutcome::Solved;
    result.assignment = std::move(best);
    result.cost = bestCost;
  } else {
    if (result.outcome == SolveOutcome::Solved) result.outcome = SolveOutcome::InfeasibleWithinBudget;
    result.assignment = x;
  }
  return result;
}

}  // namespace cbtl::solver
