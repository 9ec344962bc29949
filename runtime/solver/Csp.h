// Csp.h — one constraint satisfaction problem: a task of a program instantiated against an observation,
// with the approach's choice of which personalized constraints are hard and what the cost is.
//
// Constraint identities (for statistics and the solver's memory) are stable across regenerated CSPs of
// the same program: a hard constraint is its index in the graph, a personalized one its task and instance.
#pragma once

#include "runtime/core/Personalization.h"
#include "runtime/core/Program.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/StagedPlan.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cbtl::solver {

enum class CostKind {
  None,        // first feasible assignment wins
  Entropy,     // CBTL exploration: minimize 1 - mean Bernoulli entropy (bits) of the personalized posteriors
  Declared,    // the task's `minimize` / `maximize` expressions, summed
  Likelihood,  // exploiting a task that declares no cost: minimize 1 - the product of the personalized
               // constraints' P(holds), i.e. the most likely welcome solution; the search stops at P = 1
};

enum class ConstraintKind : std::uint8_t {
  Hard,          // a constraint of the graph
  Personal,      // a personalized instance
  PlanExecutes,  // the task's plan runs in the world (StagedPlan.h); always checked last
};

struct ConstraintRef {
  ConstraintKind kind = ConstraintKind::Hard;
  std::uint32_t index = 0;  // graph constraint index, or index into Csp::instances (0 for PlanExecutes)
  std::uint64_t identity = 0;
  bool personal() const { return kind == ConstraintKind::Personal; }
};

struct Csp {
  const rt::Program* program = nullptr;
  const ir::Task* task = nullptr;
  std::uint32_t taskIndex = 0;
  const std::vector<rt::PersonalInstance>* instances = nullptr;  // all of the task's instances
  const model::UserModel* user = nullptr;
  std::vector<double> observation;
  std::vector<double> initial;

  std::vector<ConstraintRef> constraints;      // checked in this order (personalized first)
  std::vector<std::uint32_t> scoredInstances;  // instance indices the entropy or likelihood cost reads
  std::vector<std::uint32_t> samplers;         // program sampler indices
  CostKind cost = CostKind::None;

  // Robot domains: the task's plan, evaluated skill by skill and dry-run while the solver searches
  // (StagedPlan.h; attached by the caller, runtime/approach/PlanExecution.h). Null: every constraint reads the
  // observed world and no plan is checked. With a plan, every entry of `constraints` has its stage in
  // `constraintStage`, every sampler its stage in `samplerStage`, every instance in `instanceStage`.
  StagedPlan* plan = nullptr;
  std::vector<std::uint32_t> constraintStage, samplerStage, instanceStage;
};

// Which personalized constraints a CSP contains: none (hard constraints only) or all of the task's. One exception:
// with the entropy cost (CBTL's exploration), Exclude keeps the instances of generators that explore only where
// they accept (`explore accepted`, ir::Generator::exploreAccepted).
enum class PersonalMode { Exclude, Include };

// Builds a CSP for `task`. `observation` is laid out as Program::observationSlots() says.
Csp makeCsp(const rt::Program& program, std::uint32_t taskIndex, const std::vector<rt::PersonalInstance>& instances,
            const model::UserModel& user, std::vector<double> observation, PersonalMode personal, CostKind cost);

std::string constraintName(const Csp& csp, const ConstraintRef& c);
std::string constraintLocation(const Csp& csp, const ConstraintRef& c);

}  // namespace cbtl::solver
