// `per` keys that are expressions over a generator's parameters (an item's descriptor, a table lookup): the
// learner files feedback under the key's value, the solver's instances read the model of their key, and profiles
// check the key's type.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/model/UserModel.h"
#include "runtime/solver/PersonalEvaluator.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace cbtl;

namespace {

// Three plants of two kinds. `byKind` learns one interval per kind through the item's descriptor, `byTable` one
// per kind and pot size through a constant family indexed by the plants, `byPlant` one per plant (a bare
// parameter, as before expression keys).
const char* kGarden = R"(domain garden;
enum Kind { succulent, fern }
enum PotSize { small, large }
item Plant { kind: Kind; }
items plants : Plant {
  aloe { kind: succulent },
  cactus { kind: succulent },
  maidenhair { kind: fern },
}
const potOf[plants] : PotSize = [small, large, small];
var plant : Plant;
var water : real in 0 .. 1;
sample plant ~ uniform;
sample water ~ uniform;
feedback watered(p: Plant, amount: real, good: bool);
personal byKind(p: Plant, w: real) {
  when p ~ "plant", w ~ "water";
  model interval(w, 0 .. 1) per p.kind;
  learn watered(p, w, good) => good;
}
personal byTable(p: Plant, w: real) {
  when p ~ "plant", w ~ "water";
  model interval(w, 0 .. 1) per p.kind, potOf[p];
  learn watered(p, w, good) => good;
}
personal byPlant(p: Plant, w: real) {
  when p ~ "plant", w ~ "water";
  model interval(w, 0 .. 1) per p;
  learn watered(p, w, good) => good;
}
)";

constexpr std::size_t kByKind = 0, kByTable = 1, kByPlant = 2;

struct Garden {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("garden.cbtl", kGarden);

  const rt::Program& program() const { return lp->program(); }

  void water(model::UserModel& user, const char* plant, double amount, bool good) const {
    const auto report = lp->learner().learn(
        {sim::FeedbackEvent{"watered", {sim::Value::name(plant), sim::Value::num(amount), sim::Value::num(good)}}},
        user);
    EXPECT_TRUE(report.problems.empty()) << report.problems.front();
  }
  // The person's answers: an aloe wants a little water, a maidenhair fern a lot.
  void teach(model::UserModel& user) const {
    water(user, "aloe", 0.2, true);
    water(user, "aloe", 0.8, false);
    water(user, "maidenhair", 0.7, true);
    water(user, "maidenhair", 0.1, false);
  }
  std::vector<std::string> keys(const model::UserModel& user, std::size_t generator) const {
    std::vector<std::string> out;
    for (const auto& [key, factors] : user.generator(generator).keys()) out.push_back(key);
    return out;
  }
  // P(holds) of a generator's instance at plant = `plant`, water = `amount`, and the key the solver used.
  double p(const model::UserModel& user, std::size_t generator, const char* plant, double amount,
           std::string* key = nullptr) const {
    std::vector<double> x = program().initialAssignment();
    for (const auto& v : lp->graph().variables) {
      const auto& slot = program().slot(v.id);
      if (v.name == "plant") {
        EXPECT_TRUE(program().parseName(slot.type, plant, x[slot.offset]));
      }
      if (v.name == "water") x[slot.offset] = amount;
    }
    std::vector<double> frame(64), obs(program().observationWidth() + 1);
    rt::EvalContext ctx{x.data(), obs.data(), frame.data()};
    const auto& instances = lp->instances(0);
    solver::PersonalEvaluator evaluator(program(), instances, user);
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      if (instances[i].generator != generator) continue;
      if (key != nullptr) *key = evaluator.key(i, ctx);
      return evaluator.evaluate(i, ctx).probability;
    }
    ADD_FAILURE() << "no instance of generator " << generator;
    return 0;
  }
};

}  // namespace

TEST(PerKey, FeedbackIsFiledUnderTheValueOfTheKeyExpression) {
  Garden g;
  ASSERT_TRUE(g.lp->ok());
  model::UserModel user(g.lp->graph());
  g.teach(user);
  EXPECT_EQ(g.keys(user, kByKind), (std::vector<std::string>{"fern", "succulent"}));
  EXPECT_EQ(g.keys(user, kByTable), (std::vector<std::string>{"fern|small", "succulent|small"}));
  EXPECT_EQ(g.keys(user, kByPlant), (std::vector<std::string>{"aloe", "maidenhair"}));
}

TEST(PerKey, InstancesReadTheModelOfTheirKeysValue) {
  Garden g;
  ASSERT_TRUE(g.lp->ok());
  model::UserModel user(g.lp->graph());
  g.teach(user);
  std::string key;
  // A cactus was never watered, but it is a succulent: what was learned about the aloe applies to it per kind
  // (a little water good, a lot bad), and not per plant, where the cactus has only the prior.
  EXPECT_GT(g.p(user, kByKind, "cactus", 0.2, &key), 0.5);
  EXPECT_EQ(key, "succulent");
  EXPECT_LT(g.p(user, kByKind, "cactus", 0.8), 0.5);
  EXPECT_DOUBLE_EQ(g.p(user, kByPlant, "cactus", 0.2, &key), g.p(user, kByPlant, "cactus", 0.8));
  EXPECT_EQ(key, "cactus");
  // The fern learned the opposite.
  EXPECT_GT(g.p(user, kByKind, "maidenhair", 0.7, &key), 0.5);
  EXPECT_EQ(key, "fern");
  EXPECT_LT(g.p(user, kByKind, "maidenhair", 0.1), 0.5);
  // The cactus's pot is large, a pair no feedback reached: the table-keyed model has only its prior there.
  EXPECT_DOUBLE_EQ(g.p(user, kByTable, "cactus", 0.2, &key), g.p(user, kByTable, "cactus", 0.8));
  EXPECT_EQ(key, "succulent|large");
  EXPECT_GT(g.p(user, kByTable, "aloe", 0.2, &key), 0.5);
  EXPECT_EQ(key, "succulent|small");
}

TEST(PerKey, ProfilesCheckTheTypeOfAnExpressionKey) {
  Garden g;
  ASSERT_TRUE(g.lp->ok());
  model::UserModel user(g.lp->graph());
  auto profile = [](const std::string& key) {
    return R"({"format": "cbtl-profile", "version": 1, "domain": "garden", "generators": {"byKind": {")" + key +
           R"(": {"interval": {"kind": "interval", "data": [[0.5, true]]}}}}})";
  };
  user.fromJson(profile("fern"), "p.json");
  EXPECT_EQ(user.dataCount(), 1u);
  try {
    user.fromJson(profile("cactus"), "p.json");
    ADD_FAILURE() << "a key that is no Kind was accepted";
  } catch (const model::ProfileError& e) {
    EXPECT_NE(std::string(e.what()).find("part 1 ('cactus', per p.kind) should be a member of Kind"), std::string::npos)
        << e.what();
  }
}
