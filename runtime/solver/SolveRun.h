// SolveRun.h — one call of Solver::solve: the CSP's index tables, the candidate, the cached constraint
// results and the loop of Solver.h's algorithm, in named steps. Internal to the solver (Solver.cpp is its only
// user); the algorithm and its guarantees are documented in Solver.h.
//
// A SolveRun borrows the Solver's options, RNG and constraint memories for its lifetime and draws from the RNG
// in exactly the order Solver.h describes, so a run is a pure function of (CSP, RNG state, memories).
#pragma once

#include "runtime/solver/Solver.h"

#include <cstdint>
#include <vector>

namespace cbtl::solver {

class SolveRun {
 public:
  SolveRun(const SolverOptions& options, rt::Rng& rng, std::map<std::uint64_t, Solver::Memory>& memory, const Csp& csp);
  SolveResult run();

  // Lists of lists in two flat arrays (compressed rows): the solve loop walks them for every move.
  struct Rows {
    std::vector<std::uint32_t> start{0}, items;
    void endRow() { start.push_back(static_cast<std::uint32_t>(items.size())); }
    const std::uint32_t* begin(std::size_t r) const { return items.data() + start[r]; }
    const std::uint32_t* end(std::size_t r) const { return items.data() + start[r + 1]; }
    std::size_t size(std::size_t r) const { return start[r + 1] - start[r]; }
  };

 private:
  SolveResult search();
  enum ConstraintState : std::uint8_t { Dirty, Holds, Fails };

  void buildIndexTables();
  // The rows of variables whose change re-evaluates each constraint: its own, plus in a staged plan the
  // variables the earlier stages' actions read.
  Rows dirtyRows(const Rows& own, const std::vector<std::uint32_t>& stages) const;
  // Makes the world built-ins read the state `stage` starts in (StagedPlan.h); false when it is undefined.
  bool enter(std::uint32_t stage);
  bool checkPlan();
  // Counts a dry-run rejection by failing action (SolveResult::planFailures).
  void countPlanFailure(const sim::PlanVerdict& v, const char* when);
  void attachMemories(std::map<std::uint64_t, Solver::Memory>& memory);
  void remember(std::size_t i);
  bool check(std::size_t i);
  // What checking a candidate found: a constraint fails (the first one is charged with the rejection), every
  // constraint holds, or every constraint before PlanExecutes holds and its dry run is deferred (`deferPlan`).
  enum class Verdict { Fails, Holds, Deferred };
  Verdict checkAll(bool deferPlan = false);
  // Ties whose dry run is deferred (the latest kMaxDeferredTies), and their resolution when the search ends.
  void deferTie();
  void resolveDeferredTies(std::vector<double>& best);
  static constexpr std::size_t kMaxDeferredTies = 16;
  double costOf();
  void markWritten(ir::VarId v);
  void writeDrawn(const std::vector<ir::VarId>& writes);
  // The k-th of the CSP's samplers.
  bool runSampler(std::uint32_t k);
  // The built-in `uniform` sampler: draws every component into `scratch_` first, so a failure leaves the
  // assignment untouched.
  bool drawUniform(const rt::CompiledSampler& cs);
  bool runMemorySampler(std::uint32_t i);
  // One move: samplers in a lazily drawn uniform order until one produces values (redrawn while a personalized
  // constraint of the CSP on its variables alone rejects them, up to kGuidedDraws draws in all), then every
  // sampler that depends on it (dependents_). False when none did.
  bool move();
  void buildDependents();
  bool proposalAccepted(std::uint32_t sampler);

  const SolverOptions& options_;
  rt::Rng& rng_;
  const Csp& csp_;
  const rt::Program& program_;
  const rt::ExprPool& pool_;
  PersonalEvaluator personal_;

  std::vector<double> x_;  // the candidate
  std::vector<double> frame_;
  rt::EvalContext ctx_;

  // Per constraint: the variables it reads, and the positions in the assignment of their values (the
  // sub-assignment its memory stores). Per variable: the constraints and entropy terms that read it.
  std::size_t constraintCount_ = 0, instanceCount_ = 0;
  Rows edgeVars_, edgeSlots_, readersOf_, termsOf_;

  // The staged plan (null without one): the stage the world shows, whether that is still the current
  // candidate's, whether it is defined, and which variables its actions read.
  StagedPlan* plan_ = nullptr;
  std::uint32_t stage_ = 0;
  bool stageCurrent_ = false, stageDefined_ = true;
  std::vector<std::uint8_t> actionRead_;
  // Per constraint: its cached Fails came from an undefined stage (charged to PlanExecutes), with the reason.
  std::vector<std::uint8_t> failedByStage_;
  std::vector<sim::PlanVerdict> stageVerdict_;
  std::size_t planIndex_ = SIZE_MAX;  // PlanExecutes' position in the check order (the last)
  std::vector<std::vector<double>> pendingTies_;

  std::vector<std::uint8_t> state_;
  std::vector<std::uint8_t> termDirty_;
  std::vector<PersonalValue> termValue_;

  std::vector<std::uint32_t> memorySamplers_;  // constraints with memory when the solve started
  std::vector<Solver::Memory*> memories_;
  std::size_t userSamplers_ = 0;
  // Per user sampler: the samplers that read what it writes, transitively, in CSP order. They redraw in the same
  // move, so a candidate never pairs a new value with one drawn from the old (a handover position with the
  // arm configuration sampled for the previous position).
  std::vector<std::vector<std::uint32_t>> dependents_;
  // Per user sampler: the CSP's personalized constraints whose variables it alone writes (positions in
  // csp_.constraints). A proposal they reject is drawn again, as the paper's reference draws a handover only
  // inside the shell its range-of-motion model accepts: the same candidates survive, in fewer iterations.
  std::vector<std::vector<std::uint32_t>> guards_;
  static constexpr std::uint32_t kGuidedDraws = 16;
  std::vector<std::uint32_t> order_, swaps_;

  // Sized from the program: a family of any size can be drawn by one sampler.
  std::vector<double> scratch_, args_;

  SolveResult result_;
};

}  // namespace cbtl::solver
