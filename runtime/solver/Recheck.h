// Recheck.h — the independent check a solution passes before anything acts on it.
//
// The solver accepts a candidate on cached constraint results, recomputed only for constraints whose read set
// (computed by the compiler) contains a changed variable. A wrong read set, a stale cache or a sampler that
// writes outside its declaration would let it accept an assignment that breaks a hard constraint. This check
// trusts none of that: it evaluates, from scratch and with no cache, every hard constraint the graph lists for
// the CSP's task (and, when the CSP includes them, every personalized constraint), and checks every task
// variable against its type and declared domain (bounds, allowed members, integrality, finiteness). With a
// staged plan (StagedPlan.h) the plan is unrolled afresh, every constraint is evaluated in the state its skill
// starts in, and the plan is dry-run once more (the world model may answer from its cache of verdicts: the
// executor is a pure function of state and calls, so a cached verdict is the fresh one).
//
// A violation is a bug in the runtime or a built-in: the caller must refuse the plan (never execute it) and
// report it (Planner.h, `cbtl solve` exits 70).
#pragma once

#include "runtime/solver/Csp.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::solver {

struct RecheckResult {
  std::uint64_t constraintsChecked = 0;
  std::uint64_t variablesChecked = 0;
  std::vector<std::string> violations;  // "constraint 'name' (file:line:col) does not hold", ...
  bool holds() const { return violations.empty(); }
};

RecheckResult recheck(const Csp& csp, const std::vector<double>& assignment);

}  // namespace cbtl::solver
