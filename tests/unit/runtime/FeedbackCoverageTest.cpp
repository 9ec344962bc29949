// Learning from every feedback event of every domain, against the observation of the domain's own world:
// each declared event, with typed arguments, is learned from without a crash or a problem, and each event a
// learning rule names yields labels. (Books' handoverInROM reads the user's hand pose, an observation, from
// its feature: the learner once had no observation and crashed on the first handover.)
#include "tests/unit/runtime/TestPrograms.h"

#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

using namespace cbtl;

namespace {

// A value of `type` in the simulator boundary's form; `flag` picks false/true for booleans.
sim::Value sampleValue(const rt::Program& program, const ir::TypeDesc& type, bool flag) {
  const rt::ValueType t = program.typeOf(type);
  switch (t.kind) {
    case rt::ValueKind::Bool:
      return sim::Value::num(flag ? 1 : 0);
    case rt::ValueKind::Int:
      return sim::Value::num(2);
    case rt::ValueKind::Real:
      return sim::Value::num(0.4);
    case rt::ValueKind::Text:
      return sim::Value::name("fries");
    case rt::ValueKind::Enum:
    case rt::ValueKind::Item: {
      double first = 0;
      return sim::Value::name(program.render(t, &first));
    }
    case rt::ValueKind::SE3:
      return sim::Value::vec({0.4, 0.1, 0.6, 1, 0, 0, 0});
    default:
      return sim::Value::vec(std::vector<double>(t.width, 0.2));
  }
}

class FeedbackCoverage : public ::testing::TestWithParam<const char*> {};

}  // namespace

TEST_P(FeedbackCoverage, EveryDeclaredEventIsLearnedFromWithTheWorldsObservation) {
  auto lp = app::LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + GetParam());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const rt::Program& program = lp->program();
  auto world = domains::createSimulator(lp->graph().domain, app::simulatorFacts(*lp), {}, 1);
  ASSERT_NE(world, nullptr);
  lp->syncWorld(*world);
  approach::StepWorld step;
  step.observation = approach::observationVector(program, world->observe());
  step.assignment = program.initialAssignment(step.observation);

  std::set<std::string> learnedFrom;
  for (const auto& g : lp->graph().generators) {
    for (const auto& r : g.learnRules) learnedFrom.insert(r.event);
  }
  ASSERT_FALSE(learnedFrom.empty());
  for (const auto& ev : lp->graph().feedback) {
    for (bool flag : {false, true}) {
      sim::FeedbackEvent event{ev.name, {}};
      for (const auto& p : ev.params) event.args.push_back(sampleValue(program, p.type, flag));
      model::UserModel user(lp->graph());
      const auto report = lp->learner().learn({event}, user, step);
      EXPECT_TRUE(report.problems.empty()) << ev.name << ": " << report.problems.front();
      EXPECT_TRUE(report.modelErrors.empty()) << ev.name << ": " << report.modelErrors.front();
      if (learnedFrom.count(ev.name) != 0 && flag) {
        EXPECT_GT(report.labels, 0u) << ev.name;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Domains, FeedbackCoverage,
                         ::testing::Values("/cooking/cooking.cbtl", "/cleaning/cleaning.cbtl", "/books/books.cbtl",
                                           "/feeding/feeding.cbtl"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           std::string name = param.param;
                           return name.substr(1, name.find('/', 1) - 1);
                         });
