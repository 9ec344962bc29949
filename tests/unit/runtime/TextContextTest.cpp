// Text models judged in a context (`model text(subject, context: [food, setting])`): a dip learned per food is
// preferred with that food and not with another, which the same model without context cannot represent; learned
// records carry the context of the step the feedback was about; the explanation and the profile show theta; and
// with a language model the ConstraintPrompt shows the context and the response cache is keyed by it.
#include "tests/unit/runtime/TestPrograms.h"
#include "tests/unit/textpref/ChatTestServer.h"

#include "runtime/approach/Planner.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/PersonalEvaluator.h"
#include "runtime/solver/PersonalExplanation.h"
#include "runtime/textpref/TextBackend.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

using namespace cbtl;

namespace {

// Two generators over the same dip: one judged with the food on the plate and the setting, one without context.
const char* kMealsSource = R"(domain meals;
item Dip { name: text; flavours: set<text>; }
items dips : Dip {
  ketchup { name: "ketchup", flavours: ["tangy", "sweet"] },
  bbqSauce { name: "BBQ sauce", flavours: ["smoky", "sweet"] },
  ranch { name: "ranch dressing", flavours: ["creamy"] },
}
enum Setting { alone, withFriend }
observe food : text;
observe setting : Setting;
feedback dipAnswer(offered: Dip, ideal: Dip);
var dip : Dip;
var plainDip : Dip;
sample dip ~ uniform;
sample plainDip ~ uniform;
personal dipWithMeal(d: Dip) {
  when d ~ "dip";
  model text(d, prompt: "Would the user enjoy this dip with the food on their plate?", scale: relative,
             context: [food, setting]);
  accept 0.95;
  learn dipAnswer(d, ideal) => d == ideal;
  learn dipAnswer(_, d) => true;
}
personal dipAlone(d: Dip) {
  when d ~ "plainDip";
  model text(d, scale: relative);
  accept 0.95;
  learn dipAnswer(d, ideal) => d == ideal;
  learn dipAnswer(_, d) => true;
}
)";

constexpr std::size_t kWithMeal = 0, kAlone = 1;

struct Meals {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("meals.cbtl", kMealsSource);

  const rt::Program& program() const { return lp->program(); }
  const std::vector<rt::PersonalInstance>& instances() const { return lp->instances(0); }

  std::vector<double> observation(const std::string& food, const std::string& setting) const {
    return approach::observationVector(program(),
                                       {{"food", sim::Value::name(food)}, {"setting", sim::Value::name(setting)}});
  }
  std::uint32_t instanceOf(std::size_t generator) const {
    for (std::uint32_t i = 0; i < instances().size(); ++i)
      if (instances()[i].generator == generator) return i;
    ADD_FAILURE() << "no instance of generator " << generator;
    return 0;
  }
  std::vector<double> assignment(const std::string& dip) const {
    std::vector<double> x = program().initialAssignment();
    for (const auto& v : lp->graph().variables) {
      const auto& slot = program().slot(v.id);
      EXPECT_TRUE(program().parseName(slot.type, dip, x[slot.offset])) << dip;
    }
    return x;
  }
  // P(holds) of a generator's instance with its dip set to `dip`, at a meal of `food` in `setting`.
  double p(const model::UserModel& user, std::size_t generator, const std::string& dip, const std::string& food,
           const std::string& setting = "alone") const {
    std::vector<double> x = assignment(dip), obs = observation(food, setting), frame(program().frameSize() + 1);
    rt::EvalContext ctx{x.data(), obs.data(), frame.data(), program().callContext()};
    solver::PersonalEvaluator evaluator(program(), instances(), user);
    return evaluator.evaluate(instanceOf(generator), ctx).probability;
  }
  // The user asks for `ideal` after being offered `offered`, at a meal of `food` in `setting`.
  void answer(model::UserModel& user, const std::string& offered, const std::string& ideal, const std::string& food,
              const std::string& setting = "alone") const {
    const auto report =
        lp->learner().learn({sim::FeedbackEvent{"dipAnswer", {sim::Value::name(offered), sim::Value::name(ideal)}}},
                            user, approach::StepWorld{{}, observation(food, setting)});
    ASSERT_TRUE(report.problems.empty()) << report.problems.front();
    ASSERT_TRUE(report.modelErrors.empty()) << report.modelErrors.front();
  }
};

void teachKetchupWithFriesAndBbqWithWedges(const Meals& m, model::UserModel& user) {
  for (int i = 0; i < 3; ++i) {
    m.answer(user, "ranch", "ketchup", "french fries");
    m.answer(user, "bbqSauce", "ketchup", "french fries");
    m.answer(user, "ranch", "bbqSauce", "potato wedges");
    m.answer(user, "ketchup", "bbqSauce", "potato wedges");
  }
}

TEST(TextContext, ADipLearnedPerFoodIsAcceptedWithThatFoodOnly) {
  Meals m;
  model::UserModel user(m.lp->graph());
  teachKetchupWithFriesAndBbqWithWedges(m, user);
  EXPECT_GE(m.p(user, kWithMeal, "ketchup", "french fries"), 0.95);
  EXPECT_LT(m.p(user, kWithMeal, "bbqSauce", "french fries"), 0.95);
  EXPECT_GE(m.p(user, kWithMeal, "bbqSauce", "potato wedges"), 0.95);
  EXPECT_LT(m.p(user, kWithMeal, "ketchup", "potato wedges"), 0.95);
  EXPECT_LT(m.p(user, kWithMeal, "ranch", "french fries"), 0.95);
  // Without the context the same answers cannot be told apart by food: whichever dip is accepted with fries is
  // accepted with wedges too.
  for (const char* dip : {"ketchup", "bbqSauce", "ranch"}) {
    EXPECT_DOUBLE_EQ(m.p(user, kAlone, dip, "french fries"), m.p(user, kAlone, dip, "potato wedges")) << dip;
  }
}

TEST(TextContext, TheSettingIsPartOfTheContext) {
  Meals m;
  model::UserModel user(m.lp->graph());
  for (int i = 0; i < 3; ++i) {
    m.answer(user, "ranch", "ketchup", "french fries", "alone");
    m.answer(user, "ketchup", "ranch", "french fries", "withFriend");
  }
  EXPECT_GE(m.p(user, kWithMeal, "ketchup", "french fries", "alone"), 0.95);
  EXPECT_LT(m.p(user, kWithMeal, "ketchup", "french fries", "withFriend"), 0.95);
  EXPECT_GE(m.p(user, kWithMeal, "ranch", "french fries", "withFriend"), 0.95);
}

TEST(TextContext, LearnedRecordsCarryTheContextOfTheirStep) {
  Meals m;
  model::UserModel user(m.lp->graph());
  m.answer(user, "ranch", "ketchup", "tater tots", "withFriend");
  const auto& withMeal = std::get<model::TextFactor>(user.generator(kWithMeal).factors("")[0].model());
  ASSERT_EQ(withMeal.model().history().size(), 2u);  // the offered dip (disliked) and the ideal one (liked)
  for (const auto& record : withMeal.model().history()) {
    EXPECT_EQ(record.context.fields.at("food"), std::vector<std::string>{"tater tots"});
    EXPECT_EQ(record.context.fields.at("setting"), std::vector<std::string>{"withFriend"});
  }
  const auto& alone = std::get<model::TextFactor>(user.generator(kAlone).factors("")[0].model());
  ASSERT_EQ(alone.model().history().size(), 2u);
  for (const auto& record : alone.model().history()) EXPECT_TRUE(record.context.empty());
}

TEST(TextContext, ExplanationAndProfileShowTheContextAndTheta) {
  Meals m;
  model::UserModel user(m.lp->graph());
  teachKetchupWithFriesAndBbqWithWedges(m, user);
  solver::Csp csp = solver::makeCsp(m.program(), 0, m.instances(), user, m.observation("french fries", "alone"),
                                    solver::PersonalMode::Include, solver::CostKind::None);
  const auto explained = solver::explainPersonal(csp, m.assignment("ketchup"));
  ASSERT_EQ(explained.size(), 2u);
  const auto& withMeal = explained[m.instanceOf(kWithMeal)];
  EXPECT_TRUE(withMeal.inCsp);
  EXPECT_TRUE(withMeal.holds);
  ASSERT_EQ(withMeal.text.size(), 1u);
  EXPECT_EQ(withMeal.text[0].subject, "ketchup");
  EXPECT_EQ(withMeal.text[0].context, "food: french fries; setting: alone");
  EXPECT_NE(withMeal.text[0].theta.find("ketchup (food: french fries; setting: alone)"), std::string::npos)
      << withMeal.text[0].theta;
  EXPECT_TRUE(explained[m.instanceOf(kAlone)].text[0].context.empty());

  const auto profile = nlohmann::json::parse(user.toJson());
  const auto& saved = profile["generators"]["dipWithMeal"][""]["text"];
  EXPECT_EQ(saved["theta"], withMeal.text[0].theta);
  // The profile loads back into a model that judges in context as before.
  model::UserModel loaded(m.lp->graph());
  loaded.fromJson(user.toJson(), "profile.json");
  for (const char* food : {"french fries", "potato wedges"})
    for (const char* dip : {"ketchup", "bbqSauce", "ranch"})
      EXPECT_DOUBLE_EQ(m.p(loaded, kWithMeal, dip, food), m.p(user, kWithMeal, dip, food)) << dip << " " << food;
}

// With a language model: every (dip, context) is asked once, the prompt shows the context, and a context seen
// before is answered from the cache.
TEST(TextContext, ALanguageModelIsAskedInTheContextAndItsCacheIsKeyedByIt) {
  textpref::testing::ChatTestServer server;
  server.setDefault(textpref::testing::replyRating({{"9", 1.0}}));
  auto config = textpref::textBackendConfigFromJson(
      {{"backend", "openai-compatible"}, {"base_url", server.baseUrl()}, {"model", "test-model"}, {"max_attempts", 1}});
  ASSERT_TRUE(config.ok()) << config.error().describe();
  auto backend = std::make_shared<const textpref::TextBackend>(config.value());
  Meals m;
  model::UserModel user(m.lp->graph(), backend);
  const double fries = m.p(user, kWithMeal, "ketchup", "french fries");
  const int afterFries = server.requestCount();
  EXPECT_EQ(afterFries, 3);  // relative scaling: every dip, in this context
  m.p(user, kWithMeal, "ketchup", "potato wedges");
  EXPECT_EQ(server.requestCount(), 6);  // a new context: asked again
  model::UserModel again(m.lp->graph(), backend);
  EXPECT_DOUBLE_EQ(m.p(again, kWithMeal, "ketchup", "french fries"), fries);
  EXPECT_EQ(server.requestCount(), 6);  // the shared response cache answers a context seen before
  bool sawFries = false, sawWedges = false;
  for (const auto& r : server.requests()) {
    const std::string prompt = r.body.dump();
    sawFries = sawFries || prompt.find("food: french fries; setting: alone") != std::string::npos;
    sawWedges = sawWedges || prompt.find("food: potato wedges; setting: alone") != std::string::npos;
  }
  EXPECT_TRUE(sawFries);
  EXPECT_TRUE(sawWedges);
}

// A context entry that is an item brings its declared fields: what is learned with one food reaches another of
// the same kind, and only through what the declaration says they share.
const char* kFoodsSource = R"(domain foods;
item Dip { name: text; }
items dips : Dip { ketchup { name: "ketchup" }, bbqSauce { name: "BBQ sauce" }, ranch { name: "ranch dressing" } }
item Food { name: text; kind: set<text>; }
items foods : Food {
  fries { name: "french fries", kind: ["potato", "fried"] },
  tots { name: "tater tots", kind: ["potato", "fried"] },
  carrots { name: "carrot sticks", kind: ["vegetable", "raw"] },
}
observe food : Food;
feedback dipAnswer(food: Food, offered: Dip, ideal: Dip);
var dip : Dip;
sample dip ~ uniform;
personal dipWithFood(d: Dip) {
  when d ~ "dip";
  model text(d, prompt: "Would the user enjoy this dip with the food on their plate?", scale: relative,
             context: food);
  accept 0.95;
  learn dipAnswer(_, d, ideal) => d == ideal;
  learn dipAnswer(_, _, d) => true;
}
)";

struct Foods {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("foods.cbtl", kFoodsSource);

  std::vector<double> observation(const std::string& food) const {
    return approach::observationVector(lp->program(), {{"food", sim::Value::name(food)}});
  }
  double p(const model::UserModel& user, const std::string& dip, const std::string& food) const {
    const rt::Program& program = lp->program();
    std::vector<double> x = program.initialAssignment(), obs = observation(food), frame(program.frameSize() + 1);
    const auto& slot = program.slot(lp->graph().variables.at(0).id);
    EXPECT_TRUE(program.parseName(slot.type, dip, x[slot.offset])) << dip;
    rt::EvalContext ctx{x.data(), obs.data(), frame.data(), program.callContext()};
    solver::PersonalEvaluator evaluator(program, lp->instances(0), user);
    return evaluator.evaluate(0, ctx).probability;
  }
  void answer(model::UserModel& user, const std::string& food, const std::string& offered,
              const std::string& ideal) const {
    const auto report = lp->learner().learn(
        {sim::FeedbackEvent{"dipAnswer", {sim::Value::name(food), sim::Value::name(offered), sim::Value::name(ideal)}}},
        user, approach::StepWorld{{}, observation(food)});
    ASSERT_TRUE(report.problems.empty()) << report.problems.front();
    ASSERT_TRUE(report.modelErrors.empty()) << report.modelErrors.front();
  }
};

TEST(TextContext, AnItemInTheContextCarriesWhatIsLearnedToItsKind) {
  Foods m;
  model::UserModel user(m.lp->graph());
  for (int i = 0; i < 3; ++i) {
    m.answer(user, "fries", "ranch", "ketchup");
    m.answer(user, "fries", "bbqSauce", "ketchup");
  }
  const auto& factor = std::get<model::TextFactor>(user.generator(0).factors("")[0].model());
  ASSERT_FALSE(factor.model().history().empty());
  const auto& context = factor.model().history().front().context.fields;
  EXPECT_EQ(context.at("food"), std::vector<std::string>{"fries"});
  EXPECT_EQ(context.at("food.kind"), (std::vector<std::string>{"potato", "fried"}));
  EXPECT_EQ(context.at("food.name"), std::vector<std::string>{"french fries"});
  // Tater tots were never served, but they are fried potato too: ketchup is the dip to offer with them.
  EXPECT_GE(m.p(user, "ketchup", "tots"), 0.95);
  EXPECT_LT(m.p(user, "bbqSauce", "tots"), 0.95);
  EXPECT_LT(m.p(user, "ranch", "tots"), 0.95);
  // Carrots share no descriptor with fries: only the context-free part of the answers (ketchup is liked at all)
  // reaches them, so the case against BBQ sauce is weaker there than with the fried potato.
  EXPECT_GT(m.p(user, "bbqSauce", "carrots"), m.p(user, "bbqSauce", "tots") + 0.1);
  EXPECT_GT(m.p(user, "ranch", "carrots"), m.p(user, "ranch", "tots") + 0.1);
}

TEST(TextContext, ALanguageModelSeesTheContextItemsFields) {
  textpref::testing::ChatTestServer server;
  server.setDefault(textpref::testing::replyRating({{"9", 1.0}}));
  auto config = textpref::textBackendConfigFromJson(
      {{"backend", "openai-compatible"}, {"base_url", server.baseUrl()}, {"model", "test-model"}, {"max_attempts", 1}});
  ASSERT_TRUE(config.ok()) << config.error().describe();
  Foods m;
  model::UserModel user(m.lp->graph(), std::make_shared<const textpref::TextBackend>(config.value()));
  m.p(user, "ketchup", "tots");
  ASSERT_GT(server.requestCount(), 0);
  bool sawKind = false;
  for (const auto& r : server.requests())
    sawKind = sawKind ||
              r.body.dump().find("food: tots; food.kind: potato, fried; food.name: tater tots") != std::string::npos;
  EXPECT_TRUE(sawKind);
}

}  // namespace
