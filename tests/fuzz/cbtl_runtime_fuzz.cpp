// cbtl_runtime_fuzz.cpp — libFuzzer target: the runtime on every program the compiler accepts.
//
// Each input is compiled as a .cbtl file; an input the compiler or the runtime's loader rejects is
// uninteresting (their errors are tested elsewhere). A program that loads is executed the way `cbtl` would:
// for each task (at most three), a CSP against an all-zero observation, with its personalized constraints and
// with the entropy cost, a small bounded solve, the independent re-check of a Solved result, the actions
// unrolled into calls, and every declared feedback event learned from with typed arguments. Besides crashes,
// leaks and sanitizer reports, the target aborts when a Solved result fails the re-check: the solver must
// never accept what the re-check rejects. Built only with -DCBTL_FUZZ=ON and clang (scripts/fuzz.sh runtime).
#include "app/LoadedProgram.h"
#include "runtime/approach/Planner.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Recheck.h"
#include "runtime/solver/Solver.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using namespace cbtl;

sim::Value typedValue(const rt::Program& program, const ir::TypeDesc& type, std::uint8_t salt) {
  const rt::ValueType t = program.typeOf(type);
  switch (t.kind) {
    case rt::ValueKind::Bool:
      return sim::Value::num(salt & 1);
    case rt::ValueKind::Int:
    case rt::ValueKind::Real:
      return sim::Value::num(static_cast<double>(salt) - 100.0);
    case rt::ValueKind::Text:
      return sim::Value::name(std::string(salt % 5, 'a'));
    case rt::ValueKind::Enum:
    case rt::ValueKind::Item: {
      double index = static_cast<double>(salt % 3);
      return sim::Value::name(program.render(t, &index));
    }
    default:
      return sim::Value::vec(std::vector<double>(t.width, static_cast<double>(salt) / 50.0));
  }
}

void execute(const app::LoadedProgram& lp, std::uint8_t salt) {
  const rt::Program& program = lp.program();
  const std::vector<double> observation(program.observationWidth(), 0.0);
  solver::SolverOptions options;
  options.maxIters = 200;
  options.maxImprovementAttempts = 20;
  options.numImprovements = 10;
  options.memorySize = 8;
  model::UserModel user(lp.graph());
  solver::Solver solver(options, salt);
  const std::size_t tasks = std::min<std::size_t>(lp.graph().tasks.size(), 3);
  for (std::size_t t = 0; t < tasks; ++t) {
    for (const auto choice : {approach::evaluationChoice(),
                              approach::CspChoice{solver::PersonalMode::Exclude, solver::CostKind::Entropy}}) {
      const approach::Plan plan = approach::makePlan(lp, t, observation, choice, true, solver, user);
      if (plan.refused()) {
        std::fprintf(stderr, "a Solved result failed the re-check: %s\n", plan.recheck.violations.front().c_str());
        std::abort();
      }
    }
  }
  for (const auto& ev : lp.graph().feedback) {
    sim::FeedbackEvent event{ev.name, {}};
    for (const auto& p : ev.params) event.args.push_back(typedValue(program, p.type, salt++));
    (void)lp.learner().learn({event}, user, approach::StepWorld{{}, observation});
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A path in a directory that does not exist: imports and scenes resolve next to it and cannot be read.
  auto lp = app::LoadedProgram::fromSource("/nonexistent-cbtl-fuzz/input.cbtl",
                                           std::string(reinterpret_cast<const char*>(data), size));
  if (!lp->ok()) return 0;
  execute(*lp, size > 0 ? data[size - 1] : 0);
  return 0;
}
