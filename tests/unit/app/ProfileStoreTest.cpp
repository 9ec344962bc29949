#include "app/profile/ProfileStore.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace cbtl::app::profile {
namespace {

class ProfileStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("cbtl-store-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "profiles.sqlite").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string model(int n) {
    return R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {}, "n": )" +
           std::to_string(n) + "}";
  }

  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(ProfileStoreTest, VersionsCountFromOneAndKeepTheirEventsAndModelBytes) {
  ProfileStore store(path_);
  EXPECT_FALSE(store.head("ann", "cooking"));
  EXPECT_EQ(store.recordLearning("ann", "cooking", {{EventSource::Repl, "a(1)", ""}}, model(1), 2, "learn"), 1);
  EXPECT_EQ(store.recordLearning(
                "ann", "cooking",
                {{EventSource::Simulator, "a(2)", "{\"status\":\"solved\"}"}, {EventSource::Command, "b(2)", ""}},
                model(2), 4, "learn"),
            2);
  EXPECT_EQ(store.recordLearning("ann", "cooking", {}, model(3), 4, "import of p.json"), 3);
  const auto versions = store.versions("ann", "cooking");
  ASSERT_EQ(versions.size(), 3u);
  EXPECT_EQ(versions[1].model, model(2));
  EXPECT_EQ(versions[1].labels, 4);
  EXPECT_EQ(versions[2].reason, "import of p.json");
  const auto events = store.events("ann", "cooking");
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].version, 1);
  EXPECT_EQ(events[0].source, EventSource::Repl);
  EXPECT_EQ(events[1].version, 2);
  EXPECT_EQ(events[1].solution, "{\"status\":\"solved\"}");
  EXPECT_EQ(events[2].source, EventSource::Command);
  EXPECT_LT(events[0].id, events[2].id);
  EXPECT_EQ(store.head("ann", "cooking")->version, 3);
  EXPECT_EQ(store.version("ann", "cooking", 1)->model, model(1));
  EXPECT_FALSE(store.version("ann", "cooking", 4));
  EXPECT_FALSE(store.head("ann", "books"));
  EXPECT_EQ(events[0].time.size(), std::string("2026-12-05T04:55:01.123Z").size());
}

TEST_F(ProfileStoreTest, RollbackIsANewVersionHoldingTheOldModel) {
  ProfileStore store(path_);
  store.recordLearning("ann", "cooking", {}, model(1), 1, "learn");
  store.recordLearning("ann", "cooking", {}, model(2), 2, "learn");
  EXPECT_EQ(store.rollback("ann", "cooking", 1), 3);
  const auto head = store.head("ann", "cooking");
  EXPECT_EQ(head->model, model(1));
  EXPECT_EQ(head->reason, "rollback to 1");
  EXPECT_EQ(head->labels, 1);
  EXPECT_THROW(store.rollback("ann", "cooking", 9), StoreError);
  EXPECT_THROW(store.rollback("bob", "cooking", 1), StoreError);
  EXPECT_EQ(store.versions("ann", "cooking").size(), 3u);
}

TEST_F(ProfileStoreTest, ListSummarizesEveryProfile) {
  ProfileStore store(path_);
  store.recordLearning("bob", "books", {{EventSource::Study, "e()", ""}}, model(1), 0, "learn");
  store.recordLearning("ann", "cooking", {}, model(1), 0, "learn");
  store.recordLearning("ann", "cooking", {}, model(2), 0, "learn");
  const auto all = store.list();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].user, "ann");
  EXPECT_EQ(all[0].versions, 2);
  EXPECT_EQ(all[0].head, 2);
  EXPECT_EQ(all[0].events, 0);
  EXPECT_EQ(all[1].user, "bob");
  EXPECT_EQ(all[1].events, 1);
}

TEST_F(ProfileStoreTest, BadNamesAndModelsWriteNothing) {
  ProfileStore store(path_);
  EXPECT_THROW(store.recordLearning("", "cooking", {}, model(1), 0, "learn"), StoreError);
  EXPECT_THROW(store.recordLearning("a\nb", "cooking", {}, model(1), 0, "learn"), StoreError);
  EXPECT_THROW(store.recordLearning("ann", std::string(201, 'd'), {}, model(1), 0, "learn"), StoreError);
  EXPECT_THROW(store.recordLearning("ann", "cooking", {{EventSource::Repl, "a()", ""}}, "[1, 2]", 0, "learn"),
               StoreError);
  EXPECT_THROW(store.recordLearning("ann", "cooking", {}, "{not json", 0, "learn"), StoreError);
  EXPECT_TRUE(store.list().empty());
}

TEST_F(ProfileStoreTest, RefusesFilesThatAreNotStores) {
  EXPECT_THROW(ProfileStore(path_, false), StoreError);
  EXPECT_FALSE(std::filesystem::exists(path_));
  const std::string text = (dir_ / "hello.txt").string();
  std::ofstream(text) << "hello, this is not a database at all, but it is long enough to look like a header";
  try {
    ProfileStore store(text);
    FAIL() << "opened a text file";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
  const std::string other = (dir_ / "other.sqlite").string();
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(other.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE t(x)", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(raw);
  try {
    ProfileStore store(other);
    FAIL() << "opened an unrelated SQLite database";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("not a CBTL profile store"), std::string::npos) << e.what();
  }
}

TEST_F(ProfileStoreTest, TwoConnectionsShareOneStore) {
  ProfileStore a(path_);
  ProfileStore b(path_);
  EXPECT_EQ(a.recordLearning("ann", "cooking", {}, model(1), 0, "learn"), 1);
  EXPECT_EQ(b.recordLearning("ann", "cooking", {}, model(2), 0, "learn"), 2);
  EXPECT_EQ(a.recordLearning("ann", "cooking", {}, model(3), 0, "learn"), 3);
  EXPECT_EQ(b.head("ann", "cooking")->model, model(3));
  ProfileStore reopened(path_, false);
  EXPECT_EQ(reopened.versions("ann", "cooking").size(), 3u);
}

TEST_F(ProfileStoreTest, AWriterThatCannotGetTheLockFailsAsBusy) {
  ProfileStore store(path_);
  store.recordLearning("ann", "cooking", {}, model(1), 0, "learn");
  sqlite3* holder = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &holder), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(holder, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  ProfileStore waiting(path_, false, 100);
  const auto start = std::chrono::steady_clock::now();
  try {
    waiting.recordLearning("ann", "cooking", {}, model(2), 0, "learn");
    FAIL() << "wrote while another connection held the write lock";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("busy"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(waiting.head("ann", "cooking")->version, 1);  // readers are not blocked by a writer in WAL mode
  sqlite3_exec(holder, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(holder);
  EXPECT_EQ(waiting.recordLearning("ann", "cooking", {}, model(2), 0, "learn"), 2);
}

TEST_F(ProfileStoreTest, AModelLearnedFromAnOlderVersionIsRefusedAndWritesNothing) {
  ProfileStore a(path_);
  ProfileStore b(path_);
  EXPECT_EQ(a.recordLearning("ann", "cooking", {}, model(1), 0, "learn", 0), 1);
  // b learned from version 1; a stores version 2 in the meantime; b's model would drop a's learning.
  EXPECT_EQ(a.recordLearning("ann", "cooking", {}, model(2), 0, "learn", 1), 2);
  try {
    b.recordLearning("ann", "cooking", {{EventSource::Repl, "e()", ""}}, model(3), 0, "learn", 1);
    FAIL() << "stored a model learned from version 1 over version 2";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("learned from version 1, the store now holds version 2"), std::string::npos)
        << e.what();
  }
  try {
    b.recordLearning("bo", "cooking", {}, model(1), 0, "learn", 4);
    FAIL() << "stored a model learned from a version that does not exist";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("the store now holds version 0"), std::string::npos) << e.what();
  }
  EXPECT_EQ(a.head("ann", "cooking")->model, model(2));
  EXPECT_TRUE(a.events("ann", "cooking").empty());
  EXPECT_FALSE(a.head("bo", "cooking"));
}

TEST_F(ProfileStoreTest, LearningOnTheHeadReadsAndWritesInOneTransaction) {
  ProfileStore store(path_);
  std::optional<ModelVersion> seen;
  const auto increment = [&](const std::optional<ModelVersion>& head) {
    seen = head;
    const int n = head ? static_cast<int>(nlohmann::json::parse(head->model)["n"]) : 0;
    return LearningStep{{{EventSource::Command, "tick()", ""}}, model(n + 1), n + 1, "learn"};
  };
  EXPECT_EQ(store.learnOnHead("ann", "cooking", increment), 1);
  EXPECT_FALSE(seen);
  EXPECT_EQ(store.learnOnHead("ann", "cooking", increment), 2);
  ASSERT_TRUE(seen);
  EXPECT_EQ(seen->version, 1);
  EXPECT_EQ(store.head("ann", "cooking")->model, model(2));
  EXPECT_EQ(store.events("ann", "cooking").size(), 2u);
  // While the step is being made the store is locked for writing: another connection cannot slip a version in.
  ProfileStore other(path_, false, 50);
  EXPECT_THROW(store.learnOnHead("ann", "cooking",
                                 [&](const std::optional<ModelVersion>& head) {
                                   other.recordLearning("ann", "cooking", {}, model(99), 0, "learn");
                                   return increment(head);
                                 }),
               StoreError);
  EXPECT_EQ(store.head("ann", "cooking")->version, 2);
  // A step that throws writes nothing.
  EXPECT_THROW(store.learnOnHead("ann", "cooking",
                                 [](const std::optional<ModelVersion>&) -> LearningStep {
                                   throw std::runtime_error("the learner failed");
                                 }),
               std::runtime_error);
  EXPECT_EQ(store.head("ann", "cooking")->version, 2);
  EXPECT_EQ(store.learnOnHead("ann", "cooking", increment), 3);
}

TEST_F(ProfileStoreTest, AnEmptiedFileIsRefusedAndLeftAlone) {
  std::ofstream(path_).close();
  try {
    ProfileStore store(path_);
    FAIL() << "opened a 0-byte file as a new store";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("an empty file (0 bytes)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::filesystem::file_size(path_), 0u);
  try {
    ProfileStore store(dir_.string());
    FAIL() << "opened a directory";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  // A store this process creates is fine, and so is opening it again.
  const std::string fresh = (dir_ / "fresh.sqlite").string();
  { ProfileStore created(fresh); }
  EXPECT_NO_THROW(ProfileStore(fresh, false));
}

TEST(EventSourceTest, NamesRoundTrip) {
  for (EventSource s : {EventSource::Simulator, EventSource::Repl, EventSource::Command, EventSource::Study})
    EXPECT_EQ(sourceNamed(sourceName(s)), s);
  EXPECT_FALSE(sourceNamed("typed"));
}

}  // namespace
}  // namespace cbtl::app::profile
