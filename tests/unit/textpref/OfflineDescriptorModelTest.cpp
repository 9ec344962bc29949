// The offline descriptor model: prior behaviour, learning, generalization through shared descriptors, an
// example reader's ground truth, context pairs, and state files (example data: ExampleItems.h).
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/OfflineDescriptorModel.h"
#include "tests/unit/textpref/ExampleItems.h"

#include <fstream>

namespace cbtl::textpref::testing {
namespace {

Item findBook(const std::string& name) {
  for (const auto& b : exampleBooks())
    if (b.name == name) return b;
  ADD_FAILURE() << "no book " << name;
  return {};
}

double probability(OfflineDescriptorModel& m, const Item& item, const Context& context = {}) {
  auto a = m.assess(item, context);
  EXPECT_TRUE(a.ok());
  return a.ok() ? a.value().probability : -1.0;
}

void learnOne(OfflineDescriptorModel& m, const Item& item, bool liked, const Context& context = {}) {
  FeedbackRecord r{item, context, "", liked};
  ASSERT_TRUE(m.learn(std::span(&r, 1)).ok());
}

const Item kJaneEyre{"Jane Eyre", {{"author", {"Charlotte Bronte"}}, {"genre", {"fiction", "romance", "classic"}}}};
const Item kBriefHistory{
    "A Brief History of Time",
    {{"author", {"Stephen Hawking"}}, {"genre", {"nonfiction", "science"}}, {"topic", {"universe"}}}};

TEST(OfflineDescriptorModel, UnseenItemsAreMaximallyUncertain) {
  OfflineDescriptorModel m;
  auto a = m.assess(findBook("Cosmos"), {});
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a.value().probability, 0.5, 1e-9);
  EXPECT_NEAR(a.value().entropyBits, 1.0, 1e-9);
  EXPECT_EQ(a.value().provenance, "offline-descriptor-bayes-v1");
  EXPECT_NEAR(a.value().ratings.total(), 1.0, 1e-9);
  EXPECT_NEAR(a.value().ratings.expectedProbability(), a.value().probability, 1e-9);
}

TEST(OfflineDescriptorModel, PositiveFeedbackGeneralizesToItemsSharingDescriptors) {
  OfflineDescriptorModel m;
  learnOne(m, findBook("Pride and Prejudice"), true);
  const double same = probability(m, findBook("Pride and Prejudice"));
  const double sharing = probability(m, kJaneEyre);             // fiction, romance, classic
  const double unrelated = probability(m, findBook("Cosmos"));  // nothing in common but the bias
  EXPECT_GT(same, 0.7);
  EXPECT_GT(sharing, 0.55);
  EXPECT_GT(same, sharing);
  EXPECT_GT(sharing, unrelated + 0.05);
  EXPECT_LT(unrelated, 0.52);
}

TEST(OfflineDescriptorModel, NegativeFeedbackLowersSharedItems) {
  OfflineDescriptorModel m;
  learnOne(m, findBook("Moby Dick"), false);  // fiction, adventure, classic
  EXPECT_LT(probability(m, findBook("Moby Dick")), 0.3);
  EXPECT_LT(probability(m, findBook("The Lord of the Rings")), 0.47);  // shares fiction, adventure
  EXPECT_NEAR(probability(m, findBook("Cosmos")), 0.5, 0.02);          // shares nothing
}

TEST(OfflineDescriptorModel, ConfidenceGrowsWithRepeatedFeedback) {
  OfflineDescriptorModel once, thrice;
  learnOne(once, kJaneEyre, true);
  for (int i = 0; i < 3; ++i) learnOne(thrice, kJaneEyre, true);
  const auto a = once.assess(kJaneEyre, {}).value();
  const auto b = thrice.assess(kJaneEyre, {}).value();
  EXPECT_GT(b.probability, a.probability);
  EXPECT_LT(b.entropyBits, a.entropyBits);
}

TEST(OfflineDescriptorModel, LearnsTheExampleReaderFromFeedbackOnTheNineBooks) {
  OfflineDescriptorModel m;
  const SimulatedUser user = exampleReader();
  std::vector<FeedbackRecord> feedback;
  for (const auto& book : exampleBooks()) feedback.push_back(user.react(book).value());
  ASSERT_TRUE(m.learn(feedback).ok());
  EXPECT_EQ(m.labelledCount(), 9);
  for (const auto& book : exampleBooks()) {
    const bool enjoyed = user.enjoys(book).value();
    EXPECT_EQ(probability(m, book) >= 0.5, enjoyed) << book.name;
  }
  // Unseen books: shared descriptors carry the preference over. Seven of the nine books were disliked, so the
  // bias is negative and unseen books stay near or below 0.5, but the ranking follows the hidden rule.
  const Item thriller{"Gone Girl", {{"genre", {"fiction", "mystery", "crime"}}, {"topic", {"murder"}}}};
  const Item wartime{"Band of Brothers", {{"genre", {"nonfiction", "history"}}, {"topic", {"world war ii"}}}};
  EXPECT_GT(probability(m, kBriefHistory), probability(m, wartime) + 0.1);
  EXPECT_GT(probability(m, kJaneEyre), probability(m, thriller) + 0.05);
  EXPECT_LT(probability(m, thriller), 0.45);
  const std::string theta = m.thetaText();
  EXPECT_NE(theta.find("Offline descriptor model"), std::string::npos);
  EXPECT_NE(theta.find("genre=romance"), std::string::npos);
}

TEST(OfflineDescriptorModel, FreeTextFeedbackIsReadByTheLexicon) {
  OfflineDescriptorModel m;
  std::vector<FeedbackRecord> feedback{{kJaneEyre, {}, "I loved it, thank you!", std::nullopt},
                                       {findBook("Moby Dick"), {}, "Boring, I did not like it.", std::nullopt},
                                       {findBook("Cosmos"), {}, "It has a blue cover.", std::nullopt}};
  ASSERT_TRUE(m.learn(feedback).ok());
  EXPECT_EQ(m.labelledCount(), 2);
  EXPECT_EQ(m.history().size(), 3u);
  EXPECT_GT(probability(m, kJaneEyre), 0.7);
  EXPECT_LT(probability(m, findBook("Moby Dick")), 0.3);
}

TEST(OfflineDescriptorModel, TitlesAreNotFeatures) {
  OfflineDescriptorModel m;
  const auto f = m.features(findBook("Cosmos"), {});
  for (const auto& name : f) EXPECT_EQ(name.rfind("title=", 0), std::string::npos) << name;
  EXPECT_NE(std::find(f.begin(), f.end(), "item=cosmos"), f.end());
  EXPECT_NE(std::find(f.begin(), f.end(), "topic=universe"), f.end());
}

TEST(OfflineDescriptorModel, ContextPairsSeparateTheSameDipAcrossFoods) {
  OfflineDescriptorModel m;
  const auto meals = exampleMeals();  // fries, raw vegetables, wedges, carrots, tots
  const SimulatedUser user = exampleDipUser();
  std::vector<FeedbackRecord> feedback;
  for (int meal : {0, 1})
    for (const auto& dip : exampleDips())
      feedback.push_back(user.react(dip, meals[static_cast<std::size_t>(meal)]).value());
  ASSERT_TRUE(m.learn(feedback).ok());
  const Item bbq = exampleDips()[1];
  const Item ranch = exampleDips()[2];
  // Unseen meals with the same food type: wedges (fried potato) and carrot sticks (raw vegetable).
  EXPECT_GT(probability(m, bbq, meals[2]), probability(m, bbq, meals[3]));
  EXPECT_GT(probability(m, ranch, meals[3]), probability(m, ranch, meals[2]));
  EXPECT_GT(probability(m, bbq, meals[2]), 0.5);
  EXPECT_GT(probability(m, ranch, meals[3]), 0.5);
}

TEST(OfflineDescriptorModel, StateFileRoundTrip) {
  ScratchDir dir;
  OfflineDescriptorModel m;
  learnOne(m, kJaneEyre, true);
  learnOne(m, findBook("Moby Dick"), false);
  const auto path = dir.path / "profile" / "books.json";
  ASSERT_TRUE(saveStateFile(m, path).ok());
  OfflineDescriptorModel restored;
  ASSERT_TRUE(loadStateFile(restored, path).ok());
  EXPECT_EQ(restored.history(), m.history());
  for (const auto& book : exampleBooks()) EXPECT_NEAR(probability(restored, book), probability(m, book), 1e-12);
}

TEST(OfflineDescriptorModel, CorruptOrForeignStateIsAClearError) {
  ScratchDir dir;
  OfflineDescriptorModel m;
  learnOne(m, kJaneEyre, true);
  const double before = probability(m, kJaneEyre);

  const auto garbage = dir.path / "garbage.json";
  std::ofstream(garbage) << "{\"backend\": \"offline-descriptor-bayes-v1\", \"hist";
  Status s = loadStateFile(m, garbage);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, ErrorKind::InvalidState);
  EXPECT_NE(s.error().message.find("garbage.json"), std::string::npos);

  Status missing = loadStateFile(m, dir.path / "absent.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::Io);

  nlohmann::json foreign{
      {"backend", "openai-compatible"}, {"format", 1}, {"theta", "x"}, {"history", nlohmann::json::array()}};
  EXPECT_EQ(m.loadState(foreign).error().kind, ErrorKind::InvalidState);

  nlohmann::json badOptions = m.saveState();
  badOptions["options"]["descriptorPriorVariance"] = -1.0;
  EXPECT_FALSE(m.loadState(badOptions).ok());

  nlohmann::json badRecord = m.saveState();
  badRecord["history"][0]["liked"] = "yes";
  EXPECT_FALSE(m.loadState(badRecord).ok());

  EXPECT_NEAR(probability(m, kJaneEyre), before, 1e-12);  // failed loads leave the model unchanged
}

}  // namespace
}  // namespace cbtl::textpref::testing
