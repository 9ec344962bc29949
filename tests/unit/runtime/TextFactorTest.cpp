// Text factors (`model text(subject, ...)`) in the runtime: subjects as textpref::Items, the offline descriptor
// model's prior and generalization through shared tags, relative scaling, the profile, deep copies, the solver,
// the learner's error paths, the generator's fallback, and the Books and Feeding files.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/approach/Approach.h"
#include "runtime/model/Entropy.h"
#include "runtime/model/UserModel.h"
#include "runtime/solver/Csp.h"
#include "runtime/solver/PersonalEvaluator.h"
#include "runtime/solver/Solver.h"

#include "runtime/textpref/Prompts.h"
#include "runtime/textpref/TextBackend.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace cbtl;

namespace {

// Four books: two share the tags "nonfiction", "science" and "universe"; emma and persuasion share "romance".
const char* kShelfSource = R"(domain shelf;
item Book { title: text; author: text; tags: set<text>; }
items library : Book {
  cosmos { title: "Cosmos", author: "Carl Sagan", tags: ["nonfiction", "science", "universe"] },
  briefHistory { title: "A Brief History of Time", author: "Stephen Hawking", tags: ["nonfiction", "science", "universe"] },
  emma { title: "Emma", author: "Jane Austen", tags: ["fiction", "romance", "classic"] },
  persuasion { title: "Persuasion", author: "Jane Austen", tags: ["fiction", "romance", "classic"] },
  dracula { title: "Dracula", author: "Bram Stoker", tags: ["fiction", "horror"] },
}
enum Drink { tea, coffee, water }
var book : Book;
var drink : Drink;
var greeting : text in ["hello there", "good morning"];
sample book ~ uniform;
sample drink ~ uniform;
sample greeting ~ uniform;
feedback liked(b: Book, ok: bool);
feedback drinkAnswer(d: Drink, ok: bool);
feedback greeted(g: text, ok: bool);
personal enjoys(b: Book) {
  when b ~ "*book";
  model text(b, prompt: "Would the user enjoy reading this book?", learning: "Describe which books the user likes.");
  learn liked(b, ok) => ok;
}
personal drinkPreferred(d: Drink) {
  when d ~ "drink";
  model text(d, prompt: "Would the user like this drink?", scale: relative, rating: options);
  accept 0.95;
  learn drinkAnswer(d, ok) => ok;
}
personal greetingLiked(g: text) {
  when g ~ "greeting";
  model text(g);
  fallback 0.3;
  learn greeted(g, ok) => ok;
}
)";

constexpr std::size_t kEnjoys = 0, kDrink = 1, kGreeting = 2;

struct Shelf {
  std::unique_ptr<app::LoadedProgram> lp = test::compileOrFail("shelf.cbtl", kShelfSource);

  const rt::Program& program() const { return lp->program(); }
  const std::vector<rt::PersonalInstance>& instances() const { return lp->instances(0); }

  std::uint32_t instanceOf(std::size_t generator) const {
    for (std::uint32_t i = 0; i < instances().size(); ++i) {
      if (instances()[i].generator == generator) return i;
    }
    ADD_FAILURE() << "no instance of generator " << generator;
    return 0;
  }
  std::uint32_t offsetOf(const char* name) const {
    for (const auto& v : lp->graph().variables) {
      if (v.name == name) return program().slot(v.id).offset;
    }
    ADD_FAILURE() << name;
    return 0;
  }
  // P(holds) of a generator's instance with variable `var` set to the member `value` (by name).
  double p(const model::UserModel& user, std::size_t generator, const char* var, const std::string& value) const {
    std::vector<double> x = program().initialAssignment();
    const auto& slot = program().slot(varId(var));
    EXPECT_TRUE(program().parseName(slot.type, value, x[slot.offset])) << value;
    std::vector<double> frame(64), obs(program().observationWidth() + 1);
    rt::EvalContext ctx{x.data(), obs.data(), frame.data()};
    solver::PersonalEvaluator evaluator(program(), instances(), user);
    return evaluator.evaluate(instanceOf(generator), ctx).probability;
  }
  ir::VarId varId(const char* name) const {
    for (const auto& v : lp->graph().variables) {
      if (v.name == name) return v.id;
    }
    ADD_FAILURE() << name;
    return 0;
  }
  approach::LearnReport learn(model::UserModel& user, const std::string& event, const std::string& subject,
                              bool ok) const {
    return lp->learner().learn({sim::FeedbackEvent{event, {sim::Value::name(subject), sim::Value::num(ok ? 1 : 0)}}},
                               user);
  }
};

}  // namespace

TEST(TextFactor, SubjectsBecomeItemsWithTheirDeclaredDescriptors) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  const auto& d = s.program().itemDescriptors();
  const rt::ValueType book{rt::ValueKind::Item, 1, "Book"};
  const auto* books = d.domain(book);
  ASSERT_NE(books, nullptr);
  ASSERT_EQ(books->size(), 5u);
  const textpref::Item& cosmos = (*books)[0];
  EXPECT_EQ(cosmos.name, "cosmos");
  EXPECT_EQ(cosmos.descriptors.at("title"), std::vector<std::string>{"Cosmos"});
  EXPECT_EQ(cosmos.descriptors.at("author"), std::vector<std::string>{"Carl Sagan"});
  EXPECT_EQ(cosmos.descriptors.at("tags"), (std::vector<std::string>{"nonfiction", "science", "universe"}));
  EXPECT_EQ(d.item(book, 4)->name, "dracula");
  EXPECT_EQ(d.item(book, 5), nullptr);
  EXPECT_EQ(d.item(book, -1), nullptr);
  const auto* drinks = d.domain(rt::ValueType{rt::ValueKind::Enum, 1, "Drink"});
  ASSERT_NE(drinks, nullptr);
  ASSERT_EQ(drinks->size(), 3u);
  EXPECT_EQ((*drinks)[1], (textpref::Item{"coffee", {}}));
  EXPECT_EQ(d.domain(rt::ValueType{rt::ValueKind::Text, 1, ""}), nullptr);  // texts have no fixed domain

  // Literal field values of every kind; an empty list gives no strings (the field is left out of the item).
  ir::Expr n;
  n.op = ir::Op::Num;
  n.type.kind = ir::TypeKind::Int;
  n.number = 3;
  EXPECT_EQ(rt::ItemDescriptors::fieldStrings(n, {}), std::vector<std::string>{"3"});
  n.type.kind = ir::TypeKind::Real;
  n.number = 0.25;
  EXPECT_EQ(rt::ItemDescriptors::fieldStrings(n, {}), std::vector<std::string>{"0.25"});
  ir::Expr empty;
  empty.op = ir::Op::List;
  EXPECT_TRUE(rt::ItemDescriptors::fieldStrings(empty, {}).empty());
}

TEST(TextFactor, FromSpecMakesATextFactorAndRejectsUnknownKinds) {
  ir::ModelFactor spec;
  spec.label = "taste";
  spec.kind = ir::FactorKind::Text;
  spec.prompt = "Would the user like it?";
  spec.scale = ir::TextScale::Relative;
  spec.rating = ir::TextRating::Options;
  model::Factor f = model::Factor::fromSpec(spec, 0.2);
  ASSERT_TRUE(f.isText());
  EXPECT_FALSE(f.isTable());
  const auto& text = std::get<model::TextFactor>(f.model());
  EXPECT_EQ(text.scale(), model::TextFactor::Scale::Relative);
  EXPECT_EQ(text.fallback(), 0.2);
  EXPECT_EQ(text.backendId(), textpref::OfflineDescriptorModel::kBackendId);
  // Relative scaling needs a domain; without one the probability is absolute.
  const std::vector<textpref::Item> domain{{"a", {{"tag", {"x"}}}}, {"b", {{"tag", {"y"}}}}};
  EXPECT_TRUE(f.observe(domain[0], false).ok());
  EXPECT_LT(f.probability(domain[0], {}), 0.5);
  EXPECT_NEAR(f.probability(domain[1], domain), 1.0, 1e-9);
  spec.kind = static_cast<ir::FactorKind>(200);  // no enumerator: what a corrupted graph could hold
  EXPECT_THROW(model::Factor::fromSpec(spec), std::invalid_argument);
}

TEST(TextFactor, GeneratorPromptsFrameTheQuestionWithTheItemAndTheta) {
  const auto t =
      textpref::generatorPrompts("Would the user enjoy reading this book?", "Describe which books they like.");
  const std::string prompt = textpref::renderConstraintPrompt(t, textpref::Item{"cosmos", {{"tags", {"science"}}}}, {},
                                                              "Unknown", textpref::RatingScale::Digits);
  EXPECT_NE(prompt.find("cosmos (tags: science)"), std::string::npos) << prompt;
  EXPECT_NE(prompt.find("Would the user enjoy reading this book?"), std::string::npos) << prompt;
  EXPECT_NE(prompt.find("Unknown"), std::string::npos) << prompt;
  const std::vector<textpref::FeedbackRecord> history{{textpref::Item{"cosmos", {}}, {}, "", true}};
  const std::string learning = textpref::renderLearningPrompt(t, "Unknown", history);
  EXPECT_NE(learning.find("Describe which books they like."), std::string::npos) << learning;
  EXPECT_NE(learning.find("1. cosmos"), std::string::npos) << learning;
  // A complete template is used as written; empty texts get generic ones.
  EXPECT_EQ(textpref::generatorPrompts("Rate {item}.", "").constraint, "Rate {item}.");
  EXPECT_NE(textpref::generatorPrompts("", "").constraint.find("{item}"), std::string::npos);
  EXPECT_NE(textpref::generatorPrompts("", "").learning.find("{feedback}"), std::string::npos);
}

TEST(TextFactor, PriorIsUnknownWithOneBitOfEntropy) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  ASSERT_TRUE(user.generator(kEnjoys).factors("")[0].isText());
  for (const char* b : {"cosmos", "emma", "dracula"}) {
    const double p = s.p(user, kEnjoys, "book", b);
    EXPECT_NEAR(p, 0.5, 1e-6) << b;
    EXPECT_NEAR(model::bernoulliEntropyBits(p), 1.0, 1e-6) << b;
  }
  EXPECT_NEAR(s.p(user, kGreeting, "greeting", "hello there"), 0.5, 1e-6);
  // Relative scaling of equal priors: every drink is as good as the best one.
  EXPECT_NEAR(s.p(user, kDrink, "drink", "tea"), 1.0, 1e-9);
  EXPECT_EQ(user.dataCount(), 0u);
}

TEST(TextFactor, PositiveFeedbackGeneralizesThroughSharedDescriptors) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  const auto report = s.learn(user, "liked", "cosmos", true);
  EXPECT_TRUE(report.problems.empty());
  EXPECT_TRUE(report.modelErrors.empty());
  EXPECT_EQ(report.labels, 1u);
  EXPECT_EQ(user.dataCount(), 1u);
  const double cosmos = s.p(user, kEnjoys, "book", "cosmos");
  const double sibling = s.p(user, kEnjoys, "book", "briefHistory");  // shares every tag with cosmos
  const double other = s.p(user, kEnjoys, "book", "dracula");         // shares none
  EXPECT_GT(cosmos, sibling);
  EXPECT_GT(sibling, 0.55);
  EXPECT_GT(sibling, other + 0.05);
  EXPECT_NEAR(other, 0.5, 0.05);

  // Negative feedback on emma lowers persuasion (same author and tags) below the untouched dracula.
  s.learn(user, "liked", "emma", false);
  EXPECT_LT(s.p(user, kEnjoys, "book", "persuasion"), s.p(user, kEnjoys, "book", "dracula") - 0.05);

  // The text model's history holds the subjects as items, with the liked flag.
  const auto& text = std::get<model::TextFactor>(user.generator(kEnjoys).factors("")[0].model());
  ASSERT_EQ(text.model().history().size(), 2u);
  EXPECT_EQ(text.model().history()[0].item.name, "cosmos");
  EXPECT_EQ(text.model().history()[0].item.descriptors.at("author"), std::vector<std::string>{"Carl Sagan"});
  EXPECT_EQ(text.model().history()[1].liked, std::optional<bool>(false));
}

TEST(TextFactor, EnumAndTextSubjectsLearnToo) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  s.learn(user, "drinkAnswer", "coffee", true);
  s.learn(user, "drinkAnswer", "water", false);
  // Relative: the best drink (coffee) is certain, the others are compared with it.
  EXPECT_NEAR(s.p(user, kDrink, "drink", "coffee"), 1.0, 1e-9);
  const double tea = s.p(user, kDrink, "drink", "tea"), water = s.p(user, kDrink, "drink", "water");
  EXPECT_LT(tea, 1.0);
  EXPECT_LT(water, tea);
  const auto& drinkFactor = std::get<model::TextFactor>(user.generator(kDrink).factors("")[0].model());
  const auto& drinks = *s.program().itemDescriptors().domain(rt::ValueType{rt::ValueKind::Enum, 1, "Drink"});
  EXPECT_NEAR(tea, drinkFactor.assess(drinks[0]).probability / drinkFactor.assess(drinks[1]).probability, 1e-9);

  s.learn(user, "greeted", "good morning", true);
  EXPECT_GT(s.p(user, kGreeting, "greeting", "good morning"), 0.6);
  EXPECT_NEAR(s.p(user, kGreeting, "greeting", "hello there"), 0.5, 0.05);
}

TEST(TextFactor, ProfileRoundTripsAndRejectsForeignState) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  s.learn(user, "liked", "cosmos", true);
  s.learn(user, "liked", "dracula", false);
  s.learn(user, "drinkAnswer", "tea", true);
  const std::string json = user.toJson();
  const auto parsed = nlohmann::json::parse(json);
  const auto& saved = parsed["generators"]["enjoys"][""]["text"];
  EXPECT_EQ(saved["kind"], "text");
  EXPECT_EQ(saved["backend"], textpref::OfflineDescriptorModel::kBackendId);
  EXPECT_EQ(saved["state"]["history"].size(), 2u);

  model::UserModel loaded(s.lp->graph());
  loaded.fromJson(json, "p.json");
  EXPECT_EQ(loaded.toJson(), json);
  EXPECT_EQ(loaded.dataCount(), 3u);
  EXPECT_DOUBLE_EQ(s.p(loaded, kEnjoys, "book", "briefHistory"), s.p(user, kEnjoys, "book", "briefHistory"));

  struct Case {
    std::string mutation;
    const char* expect;
  };
  auto withText = [&](const nlohmann::json& text) {
    nlohmann::json bad = parsed;
    bad["generators"]["enjoys"][""]["text"] = text;
    return bad.dump();
  };
  nlohmann::json otherBackend = saved;
  otherBackend["backend"] = "openai-compatible";
  nlohmann::json noKind = saved;
  noKind.erase("kind");
  nlohmann::json badState = saved;
  badState["state"]["history"] = 7;
  nlohmann::json badRecord = saved;
  badRecord["state"]["history"][0]["item"] = "cosmos";
  const Case cases[] = {
      {withText(otherBackend), "enjoys[\"\"].text.backend: saved by the 'openai-compatible' text backend"},
      {withText(noKind), "enjoys[\"\"].text.kind"},
      {withText(badState), "enjoys[\"\"].text.state"},
      {withText(badRecord), "enjoys[\"\"].text.state"},
      {withText(nlohmann::json{{"kind", "interval"}, {"data", nlohmann::json::array()}}), "enjoys[\"\"].text.kind"},
  };
  for (const auto& c : cases) {
    try {
      loaded.fromJson(c.mutation, "p.json");
      ADD_FAILURE() << "accepted: " << c.mutation;
    } catch (const model::ProfileError& e) {
      EXPECT_NE(std::string(e.what()).find("p.json: generators.enjoys"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
    EXPECT_EQ(loaded.toJson(), json) << "a bad profile must leave the model untouched";
  }
}

TEST(TextFactor, CopiesLearnIndependently) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  s.learn(user, "liked", "cosmos", true);
  const double before = s.p(user, kEnjoys, "book", "briefHistory");
  const std::string json = user.toJson();

  model::UserModel copy = user;  // as the evaluation agent does at every checkpoint
  EXPECT_EQ(copy.toJson(), json);
  EXPECT_DOUBLE_EQ(s.p(copy, kEnjoys, "book", "briefHistory"), before);
  s.learn(copy, "liked", "briefHistory", false);
  s.learn(copy, "liked", "cosmos", false);
  EXPECT_LT(s.p(copy, kEnjoys, "book", "briefHistory"), before - 0.1);
  EXPECT_EQ(user.toJson(), json);
  EXPECT_DOUBLE_EQ(s.p(user, kEnjoys, "book", "briefHistory"), before);

  // Assignment copies too, and reset() goes back to the prior without touching other copies.
  model::UserModel assigned(s.lp->graph());
  assigned = copy;
  assigned.reset();
  EXPECT_NEAR(s.p(assigned, kEnjoys, "book", "briefHistory"), 0.5, 1e-6);
  EXPECT_LT(s.p(copy, kEnjoys, "book", "briefHistory"), before - 0.1);
}

TEST(TextFactor, ExploitSolvePicksALikedBook) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  // Only emma is liked; its initial value (cosmos, the first book) is rejected, so the solver has to move.
  s.learn(user, "liked", "emma", true);
  for (const char* b : {"cosmos", "briefHistory", "persuasion", "dracula"}) s.learn(user, "liked", b, false);
  ASSERT_GT(s.p(user, kEnjoys, "book", "emma"), 0.5);
  for (const char* b : {"cosmos", "briefHistory", "persuasion", "dracula"})
    ASSERT_LT(s.p(user, kEnjoys, "book", b), 0.5) << b;
  const auto choice = approach::evaluationChoice();
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    solver::Solver solver({}, seed);
    const auto r = solver.solve(solver::makeCsp(s.program(), 0, s.instances(), user, {}, choice.personal, choice.cost));
    ASSERT_EQ(r.outcome, solver::SolveOutcome::Solved) << seed;
    const auto& slot = s.program().slot(s.varId("book"));
    EXPECT_EQ(s.program().render(slot.type, r.assignment.data() + slot.offset), "emma") << seed;
  }
}

TEST(TextFactor, LearnerReportsBadSubjectsAndLeavesTheModelAlone) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  model::UserModel user(s.lp->graph());
  const std::string before = user.toJson();
  const auto bad = s.learn(user, "liked", "noSuchBook", true);
  ASSERT_EQ(bad.problems.size(), 1u);
  EXPECT_NE(bad.problems[0].find("noSuchBook"), std::string::npos) << bad.problems[0];
  EXPECT_EQ(bad.labels, 0u);
  const auto badDrink = s.learn(user, "drinkAnswer", "lemonade", true);
  ASSERT_EQ(badDrink.problems.size(), 1u);
  EXPECT_NE(badDrink.problems[0].find("lemonade"), std::string::npos) << badDrink.problems[0];
  EXPECT_EQ(user.dataCount(), 0u);
  EXPECT_EQ(user.toJson(), before);
}

TEST(TextFactor, FailingBackendFallsBackOnceAndKeepsTheRecord) {
  Shelf s;
  ASSERT_TRUE(s.lp->ok());
  // A language-model backend whose server refuses connections (127.0.0.1, port 9: nothing listens there).
  textpref::TextBackendConfig config;
  config.kind = textpref::BackendKind::OpenAiCompatible;
  config.chat.baseUrl = "http://127.0.0.1:9/v1";
  config.chat.retry.maxAttempts = 1;
  config.chat.connectTimeoutMs = 500;
  config.chat.requestTimeoutMs = 1000;
  auto backend = std::make_shared<const textpref::TextBackend>(config);
  model::UserModel user(s.lp->graph(), backend);
  const auto& factor = std::get<model::TextFactor>(user.generator(kGreeting).factors("")[0].model());
  EXPECT_EQ(factor.backendId(), "openai-compatible");
  EXPECT_NEAR(s.p(user, kGreeting, "greeting", "hello there"), 0.3, 1e-12);  // the generator's fallback
  EXPECT_NEAR(s.p(user, kGreeting, "greeting", "hello there"), 0.3, 1e-12);
  EXPECT_EQ(factor.fallbackCount(), 1u) << "a failed assessment is cached until the next learn";
  EXPECT_NE(factor.lastError().find("127.0.0.1:9"), std::string::npos) << factor.lastError();
  EXPECT_NEAR(s.p(user, kEnjoys, "book", "cosmos"), 0.5, 1e-12);  // enjoys declares no fallback: 0.5

  const auto report = s.learn(user, "greeted", "hello there", true);
  EXPECT_TRUE(report.problems.empty());
  ASSERT_EQ(report.modelErrors.size(), 1u);
  EXPECT_NE(report.modelErrors[0].find("greetingLiked"), std::string::npos) << report.modelErrors[0];
  EXPECT_EQ(user.dataCount(), 1u);  // the record stays in the history
  // The profile names the backend; the offline default refuses it.
  model::UserModel offline(s.lp->graph());
  EXPECT_THROW(offline.fromJson(user.toJson(), "llm.json"), model::ProfileError);
}

// Books and Feeding load with their robot worlds; their text generators work through the user model, the
// items and the factors.
TEST(TextFactor, BooksAndFeedingLoadAndTheirTextModelsWork) {
  struct Domain {
    const char* file;
    const char* generator;
    const char* liked;
  };
  for (const Domain d : {Domain{"/books/books.cbtl", "userEnjoysBook", "prideAndPrejudice"},
                         Domain{"/feeding/feeding.cbtl", "dipPreferred", "bbqSauce"}}) {
    const std::string path = std::string(CBTL_DOMAINS_DIR) + d.file;
    auto lp = app::LoadedProgram::load(path);
    ASSERT_TRUE(lp->ok()) << lp->errors();
    EXPECT_FALSE(lp->worldPath().empty());

    model::UserModel user(lp->graph());
    std::size_t g = 0;
    while (g < user.size() && user.generator(g).spec().name != d.generator) ++g;
    ASSERT_LT(g, user.size()) << d.generator;
    const auto& spec = user.generator(g).spec();
    ASSERT_EQ(spec.factors.size(), 1u);
    EXPECT_EQ(spec.factors[0].scale, ir::TextScale::Relative);
    EXPECT_EQ(spec.factors[0].rating, ir::TextRating::Options);
    rt::ItemDescriptors items(lp->graph(), {});
    const auto* domain = items.domain(rt::ValueType{rt::ValueKind::Item, 1, spec.factors[0].feature->type.spelling});
    ASSERT_NE(domain, nullptr);
    ASSERT_GE(domain->size(), 3u);
    const auto liked = std::find_if(domain->begin(), domain->end(), [&](const auto& i) { return i.name == d.liked; });
    ASSERT_NE(liked, domain->end());
    EXPECT_FALSE(liked->descriptors.empty());

    auto& factor = user.generator(g).mutableFactors("")[0];
    ASSERT_TRUE(factor.isText());
    EXPECT_NEAR(factor.probability(domain->front(), *domain), 1.0, 1e-9);  // relative: equal priors are all best
    EXPECT_TRUE(factor.observe(*liked, true).ok());
    EXPECT_NEAR(factor.probability(*liked, *domain), 1.0, 1e-9);
    for (const auto& other : *domain) {
      if (other.name != d.liked) {
        EXPECT_LT(factor.probability(other, *domain), 1.0) << other.name;
      }
    }
    const model::UserModel copy = user;
    model::UserModel loaded(lp->graph());
    loaded.fromJson(copy.toJson(), "profile.json");
    EXPECT_EQ(loaded.toJson(), user.toJson());
  }
}
