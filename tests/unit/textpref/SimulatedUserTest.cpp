// A simulated user's ground truth, from its descriptor rule and through a language-model judge on the loopback
// server (example users: ExampleItems.h).
#include "tests/unit/textpref/TestSupport.h"

#include "tests/unit/textpref/ExampleItems.h"

namespace cbtl::textpref::testing {
namespace {

TEST(SimulatedUser, TheRuleDecidesWithoutAJudge) {
  const auto user = exampleReader();
  std::vector<std::string> enjoyed;
  const auto books = exampleBooks();
  ASSERT_EQ(books.size(), 9u);
  for (const auto& b : books)
    if (user.enjoys(b).value()) enjoyed.push_back(b.name);
  EXPECT_EQ(enjoyed, (std::vector<std::string>{"Cosmos", "Pride and Prejudice"}));
  EXPECT_NE(user.hiddenPreference().find("romance"), std::string::npos);
}

TEST(SimulatedUser, ReactionsCarryTextAndLabel) {
  const auto user = exampleReader();
  const auto liked = user.react(exampleBooks()[0]).value();
  EXPECT_EQ(liked.liked, true);
  EXPECT_FALSE(liked.text.empty());
  const auto disliked = user.react(exampleBooks()[6]).value();
  EXPECT_EQ(disliked.liked, false);
  EXPECT_NE(liked.text, disliked.text);
}

TEST(SimulatedUser, ContextTestsReadTheContext) {
  const auto meals = exampleMeals();
  const auto dipUser = exampleDipUser();
  auto wanted = [&](const Context& meal) {
    std::vector<std::string> out;
    for (const auto& d : exampleDips())
      if (dipUser.enjoys(d, meal).value()) out.push_back(d.name);
    return out;
  };
  EXPECT_EQ(wanted(meals[0]), std::vector<std::string>{"bbq sauce"});
  EXPECT_EQ(wanted(meals[1]), (std::vector<std::string>{"ranch dressing", "hummus"}));
  EXPECT_EQ(wanted(meals[4]), std::vector<std::string>{"bbq sauce"});
  EXPECT_TRUE(wanted(Context{}).empty());
}

TEST(SimulatedUser, ItemTestsMatchTheNameIgnoringCase) {
  const SimulatedUser user("one", "Only Moby Dick.", DescriptorRule{{{"item=moby dick"}}});
  const auto books = exampleBooks();
  EXPECT_TRUE(user.enjoys(books[6]).value());
  EXPECT_FALSE(user.enjoys(books[0]).value());
  EXPECT_FALSE(SimulatedUser("none", "", DescriptorRule{}).enjoys(books[0]).value());
}

TEST(SimulatedUser, LanguageModelJudgeReadsTheHiddenTextAsTheta) {
  Harness h;
  // A scripted judge: rates 9 when the prompt names Cosmos, 1 otherwise, and records the theta it was given.
  h.server.setDefault([](const httplib::Request& req, httplib::Response& res) {
    const auto body = nlohmann::json::parse(req.body);
    const std::string prompt = body["messages"][0]["content"];
    const bool cosmos = prompt.find("Cosmos") != std::string::npos;
    res.set_content(ratingBody({{cosmos ? "9" : "2", 1.0}}), "application/json");
  });
  auto user = exampleReader();
  user.useLanguageModelJudge(std::make_shared<LlmPreferenceModel>(h.client(), bookOptions()));
  const auto books = exampleBooks();
  EXPECT_TRUE(user.enjoys(books[0]).value());   // Cosmos
  EXPECT_FALSE(user.enjoys(books[6]).value());  // Moby Dick
  const auto requests = h.server.requests();
  ASSERT_EQ(requests.size(), 2u);
  const std::string prompt = requests[0].body["messages"][0]["content"];
  EXPECT_NE(prompt.find(user.hiddenPreference()), std::string::npos);
}

TEST(SimulatedUser, JudgeFailureIsAnErrorNotACrash) {
  Harness h;
  h.server.setDefault(reply(429, errorBody("quota", "insufficient_quota", "insufficient_quota")));
  auto user = exampleReader();
  user.useLanguageModelJudge(std::make_shared<LlmPreferenceModel>(h.client(), bookOptions()));
  auto r = user.react(exampleBooks()[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::QuotaExceeded);
}

}  // namespace
}  // namespace cbtl::textpref::testing
