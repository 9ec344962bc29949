// Solver.h — the paper's sampling solver: a random walk of partial resamples with a memory of satisfying
// sub-assignments (the reference's "lifelong" wrapper), made explicit and deterministic.
//
// Per iteration (the first one checks the CSP's initial assignment unchanged):
//   1. stop if a solution is known and either `maxImprovementAttempts` iterations have passed since the
//      first one or `numImprovements` further satisfying candidates (ties included) were found;
//   2. with a cost, evaluate it first and skip the constraint check when it is worse than the best
//      solution's (ties are checked, and the latest tied solution wins);
//   3. check the constraints in order, stopping at the first that fails (it is charged with the rejection);
//      without a cost the first satisfying candidate is returned;
//   4. move: try the samplers (the CSP's own, then one memory sampler per constraint that has memory) in a
//      freshly shuffled order until one produces values, and overwrite the variables it writes. Beyond the
//      reference: one of the CSP's own samplers draws again while a personalized constraint on its variables
//      alone rejects the values (up to 16 draws), and the samplers that read what it wrote draw again too.
// After `maxIters` iterations the best satisfying candidate, if any, is returned.
//
// With a staged plan (StagedPlan.h) a tie after the first solution — a candidate whose cost equals the best's and
// whose every other constraint holds — is counted as an improvement and its dry run is deferred: when the search
// stops, the latest deferred ties (up to 16) are dry-run from the newest back, and the first whose plan runs is
// the result (otherwise the best verified solution). Like checking every tie on the spot, the latest tie whose
// plan runs wins, without dry-running up to maxImprovementAttempts plans per request. Two things differ, by
// design: a deferred tie counts toward numImprovements before its dry run, and its sub-assignments do not enter
// the memories. A strictly better candidate is dry-run at once, since it moves the pruning bound.
//
// Constraint results are cached per candidate and recomputed only for constraints that read a variable
// the last move changed: the outcome is exactly that of re-checking everything, for a fraction of the cost.
// Every time a constraint is found satisfied its sub-assignment enters its memory (FIFO, `memorySize`;
// see MemoryPolicy), which lives as long as the Solver, so later CSPs of the same program start from
// values that worked before.
// Budgets are iteration counts; the same seed gives the same result.
#pragma once

#include "runtime/core/Rng.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/PersonalEvaluator.h"

#include <nlohmann/json_fwd.hpp>

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cbtl::solver {

// What enters a constraint's memory: its values whenever it is found satisfied (the reference), or only
// its values in accepted solutions (a memory of jointly consistent values; about 3x fewer iterations in
// one measured domain, but the baselines explore less — docs/runtime.md has the measurements).
enum class MemoryPolicy { EverySatisfiedCheck, Solutions };

struct SolverOptions {
  std::uint64_t maxIters = 100000;
  std::uint64_t numImprovements = 500;
  std::uint64_t maxImprovementAttempts = 10000;
  std::size_t memorySize = 100;
  bool useMemory = true;
  MemoryPolicy memoryPolicy = MemoryPolicy::EverySatisfiedCheck;
  // Set from outside (the REPL's Ctrl-C): the solve stops before its next iteration with Interrupted. Null: never.
  // Only a person sets it, so budgets stay iteration counts and runs stay deterministic.
  const std::atomic<bool>* interrupt = nullptr;
};

enum class SolveOutcome {
  Solved,                  // a satisfying assignment (the best found, with a cost)
  InfeasibleWithinBudget,  // no satisfying assignment within maxIters
  SamplersStuck,           // every sampler failed to produce a value for the current assignment
  NoSamplers,              // the CSP has no sampler and its initial assignment does not satisfy it
  Interrupted,             // SolverOptions::interrupt was set; no solution is returned (even one found before)
};

const char* toString(SolveOutcome o);

struct ConstraintStats {
  ConstraintRef ref;
  std::uint64_t evaluations = 0;
  std::uint64_t rejections = 0;  // candidates this constraint was the first to reject
};

// Candidates the plan's dry run rejected (StagedPlan.h), by failing action and status.
struct PlanFailure {
  std::uint64_t count = 0;
  std::string example;  // the detail of the first such failure
};
inline constexpr std::size_t kMaxPlanFailureKinds = 24;  // further kinds are counted as "(other failures)"

struct SolveResult {
  SolveOutcome outcome = SolveOutcome::InfeasibleWithinBudget;
  std::vector<double> assignment;  // the solution (Solved), else the last candidate
  double cost = 0;
  std::uint64_t iterations = 0;
  std::uint64_t candidatesChecked = 0;  // candidates whose constraints were checked (not pruned by cost)
  std::uint64_t improvements = 0;
  std::uint64_t prunedByCost = 0;
  std::vector<ConstraintStats> constraints;  // in the CSP's check order
  std::map<std::string, PlanFailure> planFailures;
  bool solved() const { return outcome == SolveOutcome::Solved; }
};

class Solver {
 public:
  Solver(SolverOptions options, std::uint64_t seed) : options_(options), rng_(seed) {}

  SolveResult solve(const Csp& csp);

  const SolverOptions& options() const { return options_; }
  std::size_t memoryEntries() const;

 private:
  friend class SolveRun;  // one call of solve() (SolveRun.h)
  // A FIFO of satisfying sub-assignments of one constraint, in one preallocated ring (no allocation per
  // remembered value).
  struct Memory {
    std::size_t width = 0, capacity = 0, count = 0, head = 0;
    std::vector<double> ring;
    bool empty() const { return count == 0; }
    std::size_t size() const { return count; }
    std::size_t last = 0;  // slot of the newest entry
    const double* at(std::size_t i) const {
      const std::size_t k = head + i;
      return ring.data() + (k >= capacity ? k - capacity : k) * width;
    }
    double* pushSlot() {
      if (count < capacity) {
        const std::size_t k = head + count++;
        last = k >= capacity ? k - capacity : k;
      } else {
        last = head;  // overwrite the oldest
        head = head + 1 == capacity ? 0 : head + 1;
      }
      return ring.data() + last * width;
    }
  };
  SolverOptions options_;
  rt::Rng rng_;
  std::map<std::uint64_t, Memory> memory_;

 public:
  // SolverState.cpp — checkpoints: the RNG and every constraint's memory (values as the bits of their doubles,
  // so the state is restored exactly). A solver restored from saveState() of another solver with the same
  // options solves every later CSP exactly as that one would have. restoreState throws std::runtime_error for a
  // state that does not fit (other options, a malformed document) and then leaves the solver unchanged.
  nlohmann::json saveState() const;
  void restoreState(const nlohmann::json& state);
};

}  // namespace cbtl::solver
