#include "runtime/solver/SolveRun.h"

#include "runtime/model/Entropy.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbtl::solver {

namespace {

constexpr double kMaxExactInt = 9007199254740992.0;  // 2^53

inline void copySmall(const double* from, std::size_t n, double* to) {
  for (std::size_t i = 0; i < n; ++i) to[i] = from[i];
}

// Inverts rows over [0, n): for every item, the rows that contain it.
SolveRun::Rows invert(const SolveRun::Rows& rows, std::size_t rowCount, std::size_t n) {
  std::vector<std::vector<std::uint32_t>> lists(n);
  for (std::size_t r = 0; r < rowCount; ++r) {
    for (const auto* it = rows.begin(r); it != rows.end(r); ++it) lists[*it].push_back(static_cast<std::uint32_t>(r));
  }
  SolveRun::Rows out;
  for (const auto& l : lists) {
    out.items.insert(out.items.end(), l.begin(), l.end());
    out.endRow();
  }
  return out;
}

}  // namespace

SolveRun::SolveRun(const SolverOptions& options, rt::Rng& rng, std::map<std::uint64_t, Solver::Memory>& memory,
                   const Csp& csp)
    : options_(options),
      rng_(rng),
      csp_(csp),
      program_(*csp.program),
      pool_(program_.pool()),
      personal_(program_, *csp.instances, *csp.user),
      x_(csp.initial),
      frame_(std::max<std::size_t>(program_.frameSize(), 1), 0.0),
      ctx_{x_.data(), csp.observation.data(), frame_.data(), program_.callContext()},
      plan_(csp.plan),
      scratch_(std::max<std::size_t>(program_.maxSamplerOutWidth(), 1)),
      args_(std::max<std::size_t>(program_.maxSamplerArgsWidth(), 1)) {
  buildIndexTables();
  state_.assign(constraintCount_, Dirty);
  termDirty_.assign(instanceCount_, 1);
  termValue_.resize(instanceCount_);
  result_.constraints.resize(constraintCount_);
  for (std::size_t i = 0; i < constraintCount_; ++i) result_.constraints[i].ref = csp.constraints[i];
  attachMemories(memory);
  userSamplers_ = csp.samplers.size();
  buildDependents();
  order_.resize(userSamplers_ + memorySamplers_.size());
  swaps_.resize(order_.size());
  for (std::uint32_t k = 0; k < order_.size(); ++k) order_[k] = k;
}

void SolveRun::buildIndexTables() {
  const auto& graph = program_.graph();
  constraintCount_ = csp_.constraints.size();
  for (std::size_t i = 0; i < constraintCount_; ++i) {
    const auto& ref = csp_.constraints[i];
    const std::vector<ir::VarId>& vars = ref.kind == ConstraintKind::PlanExecutes ? plan_->reads()
                                         : ref.personal() ? (*csp_.instances)[ref.index].hyperedge
                                                          : graph.constraints[ref.index].vars;
    for (ir::VarId v : vars) {
      edgeVars_.items.push_back(v);
      const auto& slot = program_.slot(v);
      for (std::uint32_t w = 0; w < slot.type.width; ++w) edgeSlots_.items.push_back(slot.offset + w);
    }
    edgeVars_.endRow();
    edgeSlots_.endRow();
  }
  readersOf_ = invert(dirtyRows(edgeVars_, csp_.constraintStage), constraintCount_, graph.variables.size());
  instanceCount_ = csp_.instances->size();
  Rows termVars;
  for (std::size_t t = 0; t < instanceCount_; ++t) {
    if (std::find(csp_.scoredInstances.begin(), csp_.scoredInstances.end(), t) != csp_.scoredInstances.end()) {
      for (ir::VarId v : (*csp_.instances)[t].hyperedge) termVars.items.push_back(v);
    }
    termVars.endRow();
  }
  termsOf_ = invert(dirtyRows(termVars, csp_.instanceStage), instanceCount_, graph.variables.size());
  actionRead_.assign(graph.variables.size(), 0);
  if (plan_ != nullptr) {
    for (ir::VarId v : plan_->reads()) actionRead_[v] = 1;
    failedByStage_.assign(constraintCount_, 0);
    stageVerdict_.resize(constraintCount_);
    for (std::size_t i = 0; i < constraintCount_; ++i)
      if (csp_.constraints[i].kind == ConstraintKind::PlanExecutes) planIndex_ = i;
  }
}

void SolveRun::buildDependents() {
  // Sampler k guards its proposals with the CSP's personalized constraints on its variables alone. Sampler j
  // depends on sampler k when it reads a variable that k, or a sampler depending on k, writes.
  const auto& samplers = program_.samplers();
  const auto writesReadBy = [&](std::uint32_t from, std::uint32_t to) {
    const auto& writes = samplers[csp_.samplers[from]].writes;
    const auto& reads = samplers[csp_.samplers[to]].source->reads;
    return std::any_of(reads.begin(), reads.end(),
                       [&](ir::VarId v) { return std::find(writes.begin(), writes.end(), v) != writes.end(); });
  };
  dependents_.assign(userSamplers_, {});
  guards_.assign(userSamplers_, {});
  for (std::uint32_t k = 0; k < userSamplers_; ++k) {
    const auto& writes = samplers[csp_.samplers[k]].writes;
    for (std::uint32_t i = 0; i < constraintCount_; ++i) {
      if (!csp_.constraints[i].personal()) continue;
      const auto& edge = (*csp_.instances)[csp_.constraints[i].index].hyperedge;
      if (std::all_of(edge.begin(), edge.end(),
                      [&](ir::VarId v) { return std::find(writes.begin(), writes.end(), v) != writes.end(); })) {
        guards_[k].push_back(i);
      }
    }
    std::vector<std::uint8_t> in(userSamplers_, 0);
    std::vector<std::uint32_t> frontier = {k};
    while (!frontier.empty()) {
      const std::uint32_t f = frontier.back();
      frontier.pop_back();
      for (std::uint32_t j = 0; j < userSamplers_; ++j) {
        if (j == k || in[j] || !writesReadBy(f, j)) continue;
        in[j] = 1;
        frontier.push_back(j);
      }
    }
    // Redraw order: a dependent after the dependents it reads from (declaration order among equals, and for
    // samplers that read each other's variables, which no order can satisfy).
    std::vector<std::uint32_t>& order = dependents_[k];
    while (order.size() < static_cast<std::size_t>(std::count(in.begin(), in.end(), 1))) {
      std::uint32_t pick = UINT32_MAX, firstLeft = UINT32_MAX;
      for (std::uint32_t j = 0; j < userSamplers_ && pick == UINT32_MAX; ++j) {
        if (in[j] != 1) continue;
        if (firstLeft == UINT32_MAX) firstLeft = j;
        bool waits = false;
        for (std::uint32_t i = 0; i < userSamplers_ && !waits; ++i) waits = i != j && in[i] == 1 && writesReadBy(i, j);
        if (!waits) pick = j;
      }
      if (pick == UINT32_MAX) pick = firstLeft;
      in[pick] = 2;
      order.push_back(pick);
    }
  }
}

bool SolveRun::proposalAccepted(std::uint32_t k) {
  // Judged in the state the sampler drew in (runSampler): a filter on proposals; check() decides.
  for (std::uint32_t i : guards_[k]) {
    const std::uint32_t instance = csp_.constraints[i].index;
    if (!personal_.holds(instance, personal_.evaluate(instance, ctx_))) return false;
  }
  return true;
}

SolveRun::Rows SolveRun::dirtyRows(const Rows& own, const std::vector<std::uint32_t>& stages) const {
  if (plan_ == nullptr) return own;
  Rows out;
  for (std::size_t r = 0; r + 1 < own.start.size(); ++r) {
    std::vector<std::uint32_t> row(own.begin(r), own.end(r));
    if (r < stages.size() && stages[r] != kAnyStage) {
      for (ir::VarId v : plan_->readsBefore(stages[r])) row.push_back(v);
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    out.items.insert(out.items.end(), row.begin(), row.end());
    out.endRow();
  }
  return out;
}

bool SolveRun::enter(std::uint32_t stage) {
  if (plan_ == nullptr || stage == kAnyStage) return true;
  if (stageCurrent_ && stage == stage_) return stageDefined_;
  stageDefined_ = plan_->enterStage(stage, ctx_);
  stage_ = stage;
  stageCurrent_ = true;
  return stageDefined_;
}

// Memory samplers: one per constraint that already has memory when the solve starts. A memory whose width no
// longer fits its constraint (another program under the same identity) starts afresh.
void SolveRun::attachMemories(std::map<std::uint64_t, Solver::Memory>& memory) {
  memories_.assign(constraintCount_, nullptr);
  if (!options_.useMemory) return;
  for (std::size_t i = 0; i < constraintCount_; ++i) {
    Solver::Memory& m = memory[csp_.constraints[i].identity];
    if (m.capacity == 0 || m.width != edgeSlots_.size(i)) {
      m = Solver::Memory{};
      m.width = edgeSlots_.size(i);
      m.capacity = std::max<std::size_t>(options_.memorySize, 1);
      m.ring.assign(m.width * m.capacity, 0.0);
    }
    memories_[i] = &m;
    if (!m.empty()) memorySamplers_.push_back(static_cast<std::uint32_t>(i));
  }
}

void SolveRun::remember(std::size_t i) {
  if (memories_[i] == nullptr) return;
  double* slot = memories_[i]->pushSlot();
  for (const auto* at = edgeSlots_.begin(i); at != edgeSlots_.end(i); ++at) *slot++ = x_[*at];
}

void SolveRun::countPlanFailure(const sim::PlanVerdict& v, const char* when) {
  // Rejections by failing action and status; the first detail of each as an example.
  auto& failures = result_.planFailures;
  std::string key = fmt::format("{}{}: {}", v.action, when, v.status);
  if (!failures.count(key) && failures.size() >= kMaxPlanFailureKinds) key = "(other failures)";
  PlanFailure& f = failures[key];
  if (f.count++ == 0) f.example = fmt::format("call {}{}{}", v.failedCall + 1, v.detail.empty() ? "" : ": ", v.detail);
}

bool SolveRun::checkPlan() {
  const sim::PlanVerdict v = plan_->check(ctx_);
  if (v.executes) return true;
  countPlanFailure(v, "");
  return false;
}

bool SolveRun::check(std::size_t i) {
  if (state_[i] != Dirty) return state_[i] == Holds;
  const auto& ref = csp_.constraints[i];
  ++result_.constraints[i].evaluations;
  bool ok, undefinedStage = false;
  if (ref.kind == ConstraintKind::PlanExecutes) {
    ok = checkPlan();
  } else if (!enter(i < csp_.constraintStage.size() ? csp_.constraintStage[i] : 0)) {
    ok = false;  // an earlier skill cannot leave a defined state for this one
    undefinedStage = true;
  } else if (ref.personal()) {
    const PersonalValue v = personal_.evaluate(ref.index, ctx_);
    ok = personal_.holds(ref.index, v);
  } else {
    ok = pool_.evalBool(program_.constraints()[ref.index].root, ctx_);
  }
  if (!failedByStage_.empty()) {
    failedByStage_[i] = undefinedStage ? 1 : 0;
    if (undefinedStage) stageVerdict_[i] = plan_->stageFailure();
  }
  state_[i] = ok ? Holds : Fails;
  if (ok && options_.memoryPolicy == MemoryPolicy::EverySatisfiedCheck) remember(i);
  return ok;
}

SolveRun::Verdict SolveRun::checkAll(bool deferPlan) {
  for (std::size_t i = 0; i < constraintCount_; ++i) {
    if (deferPlan && i == planIndex_) return Verdict::Deferred;
    if (!check(i)) {
      if (planIndex_ != SIZE_MAX && failedByStage_[i]) {
        ++result_.constraints[planIndex_].rejections;
        countPlanFailure(stageVerdict_[i], " (an earlier skill's effect)");
      } else {
        ++result_.constraints[i].rejections;
      }
      return Verdict::Fails;
    }
  }
  return Verdict::Holds;
}

void SolveRun::deferTie() {
  pendingTies_.push_back(x_);
  if (pendingTies_.size() > kMaxDeferredTies) pendingTies_.erase(pendingTies_.begin());
}

void SolveRun::resolveDeferredTies(std::vector<double>& best) {
  // The latest tie whose plan runs wins, as if each had been dry-run when it was found.
  for (auto it = pendingTies_.rbegin(); it != pendingTies_.rend(); ++it) {
    std::copy(it->begin(), it->end(), x_.begin());  // in place: ctx_ points into x_
    plan_->changed();
    stageCurrent_ = false;
    state_[planIndex_] = Dirty;
    if (check(planIndex_)) {
      best = x_;
      break;
    }
    ++result_.constraints[planIndex_].rejections;
  }
  pendingTies_.clear();
}

double SolveRun::costOf() {
  if (csp_.cost == CostKind::Entropy || csp_.cost == CostKind::Likelihood) {
    const bool entropy = csp_.cost == CostKind::Entropy;
    double sum = 0, product = 1;
    std::size_t active = 0;
    for (std::uint32_t t : csp_.scoredInstances) {
      if (termDirty_[t]) {
        if (enter(t < csp_.instanceStage.size() ? csp_.instanceStage[t] : 0)) {
          termValue_[t] = personal_.evaluate(t, ctx_);
        } else {
          termValue_[t] = PersonalValue{};  // no defined state: the instance counts as certain
          termValue_[t].applies = false;
        }
        termDirty_[t] = 0;
      }
      if (!termValue_[t].applies) continue;
      if (entropy) {
        sum += model::bernoulliEntropyBits(termValue_[t].posterior);
      } else {
        product *= termValue_[t].probability;
      }
      ++active;
    }
    if (!entropy) return 1.0 - product;
    return active == 0 ? 1.0 : 1.0 - sum / static_cast<double>(active);
  }
  if (csp_.cost == CostKind::Declared) {
    double sum = 0;
    for (std::uint32_t c : csp_.task->costs) sum += pool_.evalScalar(program_.costs()[c], ctx_);
    return sum;
  }
  return 0;
}

void SolveRun::markWritten(ir::VarId v) {
  for (const auto* c = readersOf_.begin(v); c != readersOf_.end(v); ++c) state_[*c] = Dirty;
  for (const auto* t = termsOf_.begin(v); t != termsOf_.end(v); ++t) termDirty_[*t] = 1;
  if (actionRead_[v]) {
    plan_->changed();
    stageCurrent_ = false;
  }
}

// Writes a sampler's drawn values (laid out variable after variable in `scratch_`) into the candidate.
void SolveRun::writeDrawn(const std::vector<ir::VarId>& writes) {
  std::size_t from = 0;
  for (ir::VarId v : writes) {
    const auto& slot = program_.slot(v);
    copySmall(scratch_.data() + from, slot.type.width, x_.data() + slot.offset);
    from += slot.type.width;
    markWritten(v);
  }
}

bool SolveRun::runSampler(std::uint32_t k) {
  const std::uint32_t stage = k < csp_.samplerStage.size() ? csp_.samplerStage[k] : kAnyStage;
  if (plan_ != nullptr && stage != kAnyStage) {
    // A proposal needs no exact state: the latest one of its stage (StagedPlan.h), so no effects are computed.
    plan_->enterRecentStage(stage);
    stageCurrent_ = false;
  }
  const rt::CompiledSampler& cs = program_.samplers()[csp_.samplers[k]];
  if (cs.impl == nullptr) return drawUniform(cs);
  double* const args = args_.data();
  std::size_t at = 0;
  for (std::uint32_t a : cs.args) {
    pool_.eval(a, ctx_, args + at);
    at += pool_.width(a);
  }
  if (!cs.impl(*program_.callContext(), std::span<const double>(args, at), std::span<const std::uint16_t>(cs.argWidths),
               rng_, std::span<double>(scratch_.data(), cs.outWidth))) {
    return false;
  }
  writeDrawn(cs.writes);
  return true;
}

bool SolveRun::drawUniform(const rt::CompiledSampler& cs) {
  double* const scratch = scratch_.data();
  std::size_t at = 0;
  for (std::size_t k = 0; k < cs.writes.size(); ++k) {
    const auto& plan = cs.uniform[k];
    const auto& slot = program_.slot(cs.writes[k]);
    for (std::size_t c = 0; c < slot.type.width; ++c, ++at) {
      switch (plan.kind) {
        case rt::UniformPlan::Kind::Bool:
          scratch[at] = rng_.coin() ? 1 : 0;
          break;
        case rt::UniformPlan::Kind::Choice:
          if (plan.observedFlags) {
            // The members the observation lists (flags in member order; choices are the member indices).
            const double* flags = csp_.observation.data() + *plan.observedFlags;
            std::size_t listed = 0;
            for (double m : plan.choices) listed += flags[static_cast<std::size_t>(m)] != 0 ? 1 : 0;
            if (listed == 0) return false;
            std::size_t pick = rng_.index(listed);
            for (double m : plan.choices) {
              if (flags[static_cast<std::size_t>(m)] == 0) continue;
              if (pick-- == 0) {
                scratch[at] = m;
                break;
              }
            }
          } else {
            scratch[at] = plan.choices[rng_.index(plan.choices.size())];
          }
          break;
        case rt::UniformPlan::Kind::Int: {
          // Bounds are clamped to the integers a double holds exactly (and int64 can convert).
          const double lo = std::max(std::ceil(pool_.evalScalar(plan.lo[c], ctx_)), -kMaxExactInt);
          const double hi = std::min(std::floor(pool_.evalScalar(plan.hi[c], ctx_)), kMaxExactInt);
          if (!(lo <= hi)) return false;
          scratch[at] =
              static_cast<double>(rng_.uniformInt(static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi)));
          break;
        }
        case rt::UniformPlan::Kind::Real: {
          const double lo = pool_.evalScalar(plan.lo[c], ctx_), hi = pool_.evalScalar(plan.hi[c], ctx_);
          if (!(lo <= hi) || !std::isfinite(hi - lo)) return false;
          scratch[at] = rng_.uniform(lo, hi);
          break;
        }
      }
    }
  }
  writeDrawn(cs.writes);
  return true;
}

bool SolveRun::runMemorySampler(std::uint32_t i) {
  const Solver::Memory& m = *memories_[i];
  if (m.empty()) return false;
  const double* sub = m.at(rng_.index(m.size()));
  for (const auto* at = edgeSlots_.begin(i); at != edgeSlots_.end(i); ++at) x_[*at] = *sub++;
  for (const auto* v = edgeVars_.begin(i); v != edgeVars_.end(i); ++v) markWritten(*v);
  return true;
}

// A uniformly random order, drawn lazily (Fisher-Yates one position at a time): the first sampler usually
// succeeds, so most moves cost one draw instead of a full shuffle. `order_` starts every move as the identity;
// the swaps are undone afterwards instead of rewriting the whole array.
bool SolveRun::move() {
  bool moved = false;
  std::size_t pos = 0;
  for (; pos < order_.size() && !moved; ++pos) {
    swaps_[pos] = static_cast<std::uint32_t>(pos + rng_.index(order_.size() - pos));
    std::swap(order_[pos], order_[swaps_[pos]]);
    const std::uint32_t k = order_[pos];
    moved = k < userSamplers_ ? runSampler(k) : runMemorySampler(memorySamplers_[k - userSamplers_]);
    if (moved && k < userSamplers_) {
      for (std::uint32_t draw = 1; draw < kGuidedDraws && !proposalAccepted(k); ++draw) runSampler(k);
      for (std::uint32_t j : dependents_[k]) runSampler(j);
    }
  }
  while (pos-- > 0) std::swap(order_[pos], order_[swaps_[pos]]);
  return moved;
}

SolveResult SolveRun::run() {
  SolveResult result = search();
  if (plan_ != nullptr) plan_->enterStage(0, ctx_);  // the caller's built-ins read the observed world again
  return result;
}

SolveResult SolveRun::search() {
  bool found = false;
  double bestCost = std::numeric_limits<double>::infinity();
  std::vector<double> best;
  std::uint64_t attempts = 0;
  for (std::uint64_t iter = 0; iter < options_.maxIters; ++iter) {
    if (options_.interrupt != nullptr && options_.interrupt->load(std::memory_order_relaxed)) {
      result_.outcome = SolveOutcome::Interrupted;
      result_.assignment = x_;
      return std::move(result_);
    }
    if (found && (attempts >= options_.maxImprovementAttempts || result_.improvements >= options_.numImprovements ||
                  (csp_.cost == CostKind::Likelihood && bestCost <= 0))) {
      break;  // (nothing is more likely than certain)
    }
    if (found) ++attempts;
    ++result_.iterations;
    const double cost = csp_.cost == CostKind::None ? 0 : costOf();
    if (cost > bestCost) {
      ++result_.prunedByCost;
    } else {
      ++result_.candidatesChecked;
      // A tie after the first solution defers its dry run to the end (Solver.h): only the latest matters.
      const bool tie = found && cost == bestCost && csp_.cost != CostKind::None;
      const Verdict v = checkAll(plan_ != nullptr && tie);
      if (v == Verdict::Deferred) {
        ++result_.improvements;
        deferTie();
      } else if (v == Verdict::Holds) {
        if (options_.memoryPolicy == MemoryPolicy::Solutions) {
          for (std::size_t i = 0; i < constraintCount_; ++i) remember(i);
        }
        if (found) ++result_.improvements;
        found = true;
        if (csp_.cost == CostKind::None) {
          result_.outcome = SolveOutcome::Solved;
          result_.assignment = x_;
          result_.cost = 0;
          return std::move(result_);
        }
        if (cost < bestCost) pendingTies_.clear();  // they tied a worse solution
        best = x_;
        bestCost = cost;
      }
    }
    if (order_.empty()) {
      result_.outcome = found ? SolveOutcome::Solved : SolveOutcome::NoSamplers;
      break;
    }
    if (!move()) {
      result_.outcome = found ? SolveOutcome::Solved : SolveOutcome::SamplersStuck;
      break;
    }
  }
  if (found && !pendingTies_.empty()) resolveDeferredTies(best);
  if (found) {
    result_.outcome = SolveOutcome::Solved;
    result_.assignment = std::move(best);
    result_.cost = bestCost;
  } else {
    if (result_.outcome == SolveOutcome::Solved) result_.outcome = SolveOutcome::InfeasibleWithinBudget;
    result_.assignment = x_;
  }
  return std::move(result_);
}

}  // namespace cbtl::solver
