#include "app/study/StudyRecords.h"

#include "app/profile/ProfileStore.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cbtl::app::study {
namespace {

using Status = RecordOutcome::Status;

class StudyRecordsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("cbtl-study-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "study.sqlite").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static NewRecord page(const std::string& participant, std::int64_t trial, const std::string& response = "{}",
                        const std::string& kind = "meal_rating", int meal = 1) {
    return {participant, trial, kind, meal, 1000 * (trial + 1), 250 + trial, response};
  }

  // The message of the StudyError that `f` throws, or a failure.
  template <typename F>
  static std::string errorOf(F f) {
    try {
      f();
    } catch (const StudyError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no StudyError";
    return "";
  }

  static bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  }

  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(StudyRecordsTest, BeginCreatesOnceThenReturnsTheStoredParticipant) {
  StudyRecords study(path_);
  EXPECT_FALSE(study.participant("p1"));
  const Participant first = study.begin("p1", 18446744073709551615ull, R"({"arm": "cbtl-first"})");
  EXPECT_EQ(first.id, "p1");
  EXPECT_EQ(first.seed, 18446744073709551615ull);  // 2^64 - 1 survives SQLite's signed integers
  EXPECT_EQ(first.options, R"({"arm": "cbtl-first"})");
  EXPECT_FALSE(first.completed);
  EXPECT_EQ(first.created.size(), std::string("2026-12-05T04:55:01.123Z").size());
  EXPECT_EQ(first.created.back(), 'Z');
  const Participant again = study.begin("p1", 7, R"({"arm": "baseline-first"})");  // a reload
  EXPECT_EQ(again.seed, first.seed);
  EXPECT_EQ(again.options, first.options);
  EXPECT_EQ(again.created, first.created);
  EXPECT_EQ(study.participants().size(), 1u);
}

TEST_F(StudyRecordsTest, ParticipantIdsAreCheckedAndNamedSafely) {
  StudyRecords study(path_);
  EXPECT_NO_THROW(study.begin("Prolific_5f3a.b-9", 1, "{}"));
  EXPECT_NO_THROW(study.begin(std::string(64, 'x'), 1, "{}"));
  for (const std::string& bad : {std::string(), std::string(65, 'x'), std::string("a b"), std::string("a/b"),
                                 std::string("ü"), std::string("a'b")})
    EXPECT_THROW(study.begin(bad, 1, "{}"), StudyError) << bad;
  const std::string message = errorOf([&] { study.begin("evil\x01\n'id", 1, "{}"); });
  EXPECT_EQ(message.rfind(path_, 0), 0u) << message;
  EXPECT_TRUE(contains(message, R"('evil\x01\x0a\'id')")) << message;
  EXPECT_TRUE(contains(errorOf([&] { study.participant(std::string(500, 'y')); }), "(500 bytes)"));
  EXPECT_THROW(study.records("a b"), StudyError);
  EXPECT_THROW(study.complete(""), StudyError);
  EXPECT_FALSE(isParticipantId("a:b"));
  EXPECT_TRUE(isParticipantId("A-z.0_9"));
  EXPECT_EQ(study.participants().size(), 2u);
}

TEST_F(StudyRecordsTest, OptionsMustBeAJsonObject) {
  StudyRecords study(path_);
  EXPECT_THROW(study.begin("p1", 1, "[1]"), StudyError);
  EXPECT_THROW(study.begin("p1", 1, "{oops"), StudyError);
  EXPECT_THROW(study.begin("p1", 1, ""), StudyError);
  EXPECT_TRUE(study.participants().empty());
}

TEST_F(StudyRecordsTest, ParticipantsComeInCreationOrder) {
  StudyRecords study(path_);
  for (const char* id : {"zed", "amy", "mid"}) study.begin(id, 1, "{}");
  study.begin("amy", 2, "{}");
  const auto all = study.participants();
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].id, "zed");
  EXPECT_EQ(all[1].id, "amy");
  EXPECT_EQ(all[2].id, "mid");
}

TEST_F(StudyRecordsTest, TrialsCountFromZeroWithoutGaps) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  EXPECT_EQ(study.nextTrial("p1"), 0);
  const RecordOutcome first = study.record(page("p1", 0, R"({"consent": true})", "consent", 0));
  EXPECT_EQ(first.status, Status::Stored);
  EXPECT_EQ(first.record.trialIndex, 0);
  EXPECT_EQ(first.record.kind, "consent");
  EXPECT_EQ(first.record.recorded.size(), std::string("2026-12-05T04:55:01.123Z").size());
  EXPECT_EQ(study.record(page("p1", 1, R"({"preference": 4})")).status, Status::Stored);
  EXPECT_EQ(study.nextTrial("p1"), 2);
  const std::string ahead = errorOf([&] { study.record(page("p1", 4)); });
  EXPECT_TRUE(contains(ahead, "expected trial 2, got 4")) << ahead;
  EXPECT_EQ(ahead.rfind(path_, 0), 0u) << ahead;
  const auto records = study.records("p1");
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].response, R"({"preference":4})");
  EXPECT_EQ(records[1].meal, 1);
  EXPECT_EQ(records[1].elapsedMs, 2000);
  EXPECT_EQ(records[1].rtMs, 251);
  EXPECT_TRUE(study.records("nobody").empty());
}

TEST_F(StudyRecordsTest, AResentRecordIsAReplayThatWritesNothing) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  const RecordOutcome stored = study.record(page("p1", 0, R"({"preference": 4, "why": "crispy"})"));
  NewRecord resent = page("p1", 0, R"({ "why" : "crispy", "preference" : 4 })");  // the same JSON value
  resent.elapsedMs = 99999;                                                       // the browser's retry clock
  const RecordOutcome replay = study.record(resent);
  EXPECT_EQ(replay.status, Status::Replayed);
  EXPECT_EQ(replay.record.elapsedMs, stored.record.elapsedMs);
  EXPECT_EQ(replay.record.recorded, stored.record.recorded);
  EXPECT_EQ(replay.record.response, R"({"preference":4,"why":"crispy"})");
  EXPECT_EQ(study.nextTrial("p1"), 1);
}

TEST_F(StudyRecordsTest, AConflictingReplayIsRefused) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  study.record(page("p1", 0, R"({"preference": 4})"));
  const std::string response = errorOf([&] { study.record(page("p1", 0, R"({"preference": 5})")); });
  EXPECT_TRUE(contains(response, "trial 0 of participant 'p1' is already recorded, differently (the response)"))
      << response;
  const std::string kind = errorOf([&] { study.record(page("p1", 0, R"({"preference": 4})", "questionnaire")); });
  EXPECT_TRUE(contains(kind, "kind 'meal_rating' vs 'questionnaire'")) << kind;
  const std::string meal = errorOf([&] { study.record(page("p1", 0, R"({"preference": 4})", "meal_rating", 2)); });
  EXPECT_TRUE(contains(meal, "meal 1 vs 2")) << meal;
  EXPECT_EQ(study.records("p1")[0].response, R"({"preference":4})");
}

TEST_F(StudyRecordsTest, UnknownParticipantsAreRefused) {
  StudyRecords study(path_);
  EXPECT_TRUE(contains(errorOf([&] { study.record(page("ghost", 0)); }), "no participant 'ghost'"));
  EXPECT_THROW(study.nextTrial("ghost"), StudyError);
  EXPECT_THROW(study.complete("ghost"), StudyError);
  EXPECT_TRUE(study.participants().empty());
}

TEST_F(StudyRecordsTest, ACompletedParticipantTakesNoNewRecordsButReplaysSucceed) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  study.record(page("p1", 0));
  study.complete("p1");
  const std::string completed = *study.participant("p1")->completed;
  study.complete("p1");  // again: the first time stays
  EXPECT_EQ(*study.participant("p1")->completed, completed);
  EXPECT_EQ(study.record(page("p1", 0)).status, Status::Replayed);
  const std::string late = errorOf([&] { study.record(page("p1", 1)); });
  EXPECT_TRUE(contains(late, "participant 'p1' completed the study at " + completed)) << late;
  EXPECT_EQ(study.begin("p1", 1, "{}").completed, completed);
}

TEST_F(StudyRecordsTest, BadRecordsWriteNothing) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  NewRecord r = page("p1", 0);
  r.elapsedMs = -1;
  EXPECT_TRUE(contains(errorOf([&] { study.record(r); }), "negative time"));
  r = page("p1", 0);
  r.rtMs = -5;
  EXPECT_THROW(study.record(r), StudyError);
  EXPECT_TRUE(contains(errorOf([&] { study.record(page("p1", 0, "{\"a\": ")); }), "is not JSON"));
  EXPECT_THROW(study.record(page("p1", 0, "")), StudyError);
  EXPECT_THROW(study.record(page("p1", 0, "{} {}")), StudyError);
  for (const std::string& kind :
       {std::string(), std::string(41, 'k'), std::string("Meal"), std::string("meal1"), std::string("meal rating")})
    EXPECT_THROW(study.record(page("p1", 0, "{}", kind)), StudyError) << kind;
  EXPECT_NO_THROW(study.record(page("p1", 0, "{}", std::string(40, 'k'), 0)));
  EXPECT_THROW(study.record(page("p1", 1, "{}", "meal_rating", kMeals + 1)), StudyError);
  EXPECT_THROW(study.record(page("p1", 1, "{}", "meal_rating", -1)), StudyError);
  EXPECT_THROW(study.record(page("p1", -1)), StudyError);
  EXPECT_EQ(study.nextTrial("p1"), 1);
}

TEST_F(StudyRecordsTest, AResponseIsAnyJsonValueStoredCompactInTheSendersKeyOrder) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  const std::vector<std::pair<std::string, std::string>> cases{{" [1, 2,\n 3] ", "[1,2,3]"},
                                                               {"\"text\"", "\"text\""},
                                                               {"null", "null"},
                                                               {"3.5", "3.5"},
                                                               {R"({"b": 1, "a": [true]})", R"({"b":1,"a":[true]})"}};
  for (std::size_t i = 0; i < cases.size(); ++i)
    EXPECT_EQ(study.record(page("p1", static_cast<std::int64_t>(i), cases[i].first)).record.response, cases[i].second);
  const auto records = study.records("p1");
  ASSERT_EQ(records.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(records[i].response, cases[i].second);
}

TEST_F(StudyRecordsTest, ExportJsonLinesHasOneObjectPerRecordByParticipantThenTrial) {
  StudyRecords study(path_);
  study.begin("zed", 1, "{}");
  study.begin("amy", 2, "{}");
  study.record(page("amy", 0, R"({"x": 1})"));
  study.record(page("zed", 0, "[3]", "consent", 0));
  study.record(page("zed", 1, "\"done\"", "debrief", 5));
  std::ostringstream out;
  study.exportJsonLines(out);
  std::istringstream in(out.str());
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0]["participant"], "zed");
  EXPECT_EQ(lines[0]["trial_index"], 0);
  EXPECT_EQ(lines[0]["kind"], "consent");
  EXPECT_EQ(lines[0]["meal"], 0);
  EXPECT_EQ(lines[0]["elapsed_ms"], 1000);
  EXPECT_EQ(lines[0]["rt_ms"], 250);
  EXPECT_EQ(lines[0]["response"], nlohmann::json::array({3}));  // a JSON value, not a string
  EXPECT_EQ(lines[0]["recorded"], study.records("zed")[0].recorded);
  EXPECT_EQ(lines[1]["participant"], "zed");
  EXPECT_EQ(lines[1]["response"], "done");
  EXPECT_EQ(lines[1]["meal"], 5);
  EXPECT_EQ(lines[2]["participant"], "amy");
  EXPECT_EQ(lines[2]["response"]["x"], 1);
  EXPECT_EQ(out.str().rfind(R"({"participant":"zed","trial_index":0,"kind":"consent","meal":0,)", 0), 0u);
}

TEST_F(StudyRecordsTest, ExportCsvQuotesFieldsAsRfc4180Says) {
  StudyRecords study(path_);
  study.begin("p1", 1, "{}");
  study.record(page("p1", 0, R"({"say": "a, \"b\"\nc"})"));
  study.record(page("p1", 1, "42", "likert", 3));
  std::ostringstream out;
  study.exportCsv(out);
  const auto records = study.records("p1");
  EXPECT_EQ(out.str(),
            "participant,trial_index,kind,meal,elapsed_ms,rt_ms,response,recorded\r\n"
            "p1,0,meal_rating,1,1000,250,\"{\"\"say\"\":\"\"a, \\\"\"b\\\"\"\\nc\"\"}\"," +
                records[0].recorded +
                "\r\n"
                "p1,1,likert,3,2000,251,42," +
                records[1].recorded + "\r\n");
}

TEST_F(StudyRecordsTest, ARestartedServerReadsWhatWasWritten) {
  {
    StudyRecords study(path_);
    study.begin("p1", 42, R"({"arm": "a"})");
    study.record(page("p1", 0, R"({"preference": 2})"));
    study.record(page("p1", 1, R"({"preference": 5})"));
    study.complete("p1");
    study.begin("p2", 43, "{}");
    study.record(page("p2", 0));
  }
  StudyRecords restarted(path_, false);
  const auto all = restarted.participants();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].seed, 42u);
  EXPECT_EQ(all[0].options, R"({"arm": "a"})");
  EXPECT_TRUE(all[0].completed);
  EXPECT_FALSE(all[1].completed);
  EXPECT_EQ(restarted.records("p1").size(), 2u);
  EXPECT_EQ(restarted.records("p1")[1].response, R"({"preference":5})");
  EXPECT_EQ(restarted.nextTrial("p2"), 1);
  EXPECT_EQ(restarted.record(page("p2", 1)).status, Status::Stored);
}

TEST_F(StudyRecordsTest, TwoConnectionsShareOneFile) {
  StudyRecords a(path_);
  StudyRecords b(path_);
  a.begin("p1", 1, "{}");
  EXPECT_EQ(b.record(page("p1", 0)).status, Status::Stored);
  EXPECT_EQ(a.record(page("p1", 0)).status, Status::Replayed);
  EXPECT_EQ(a.record(page("p1", 1)).status, Status::Stored);
  EXPECT_EQ(b.nextTrial("p1"), 2);
}

TEST_F(StudyRecordsTest, SharesTheFileWithAProfileStoreOpenedFirst) {
  const std::string model = R"({"format": "cbtl-profile", "version": 1})";
  {
    profile::ProfileStore profiles(path_);
    profiles.recordLearning("p1", "cooking", {{profile::EventSource::Study, "likes(fries)", ""}}, model, 1, "learn");
  }
  StudyRecords study(path_, false);
  study.begin("p1", 1, "{}");
  study.record(page("p1", 0));
  profile::ProfileStore profiles(path_, false);
  EXPECT_EQ(profiles.head("p1", "cooking")->model, model);
  EXPECT_EQ(profiles.recordLearning("p1", "cooking", {}, model, 2, "learn"), 2);
  EXPECT_EQ(study.records("p1").size(), 1u);
}

TEST_F(StudyRecordsTest, SharesTheFileWithAProfileStoreOpenedAfter) {
  {
    StudyRecords study(path_);
    study.begin("p1", 1, "{}");
    study.record(page("p1", 0));
  }
  profile::ProfileStore profiles(path_, false);
  EXPECT_TRUE(profiles.list().empty());
  EXPECT_EQ(profiles.recordLearning("p1", "cooking", {}, "{}", 0, "learn"), 1);
  StudyRecords study(path_, false);
  EXPECT_EQ(study.nextTrial("p1"), 1);
  EXPECT_EQ(profiles.list().size(), 1u);
}

TEST_F(StudyRecordsTest, RefusesFilesThatAreNotStudyDatabases) {
  EXPECT_TRUE(contains(errorOf([&] { StudyRecords(path_, false); }), "no such study database"));
  EXPECT_FALSE(std::filesystem::exists(path_));
  const std::string text = (dir_ / "hello.txt").string();
  std::ofstream(text) << "hello, this is not a database at all, but it is long enough to look like a header";
  EXPECT_EQ(errorOf([&] { StudyRecords study(text); }).rfind(text, 0), 0u);
  const std::string other = (dir_ / "other.sqlite").string();
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(other.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE t(x)", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(raw);
  const std::string message = errorOf([&] { StudyRecords study(other); });
  EXPECT_TRUE(contains(message, "not a CBTL profile store")) << message;
}

TEST_F(StudyRecordsTest, RefusesNewerStudyTables) {
  { StudyRecords study(path_); }
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(raw, "UPDATE study_meta SET value = 3 WHERE key = 'schema_version'", nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(raw);
  const std::string message = errorOf([&] { StudyRecords study(path_); });
  EXPECT_TRUE(contains(message, "study tables of schema 3, newer than this cbtl's 2")) << message;
  EXPECT_NO_THROW(profile::ProfileStore(path_, false));  // the profiles are still readable
}

// A database of schema 1 (before participants' keys) gets the keys' table when opened, and keeps its participants.
TEST_F(StudyRecordsTest, ASchemaOneDatabaseGetsTheKeysTable) {
  {
    StudyRecords study(path_);
    study.begin("p1", 0, "{}");
  }
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "DROP TABLE study_keys; UPDATE study_meta SET value = 1 WHERE key = 'schema_version'",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(raw);
  StudyRecords study(path_);
  ASSERT_TRUE(study.participant("p1").has_value());
  EXPECT_FALSE(study.keyHash("p1").has_value());
  EXPECT_TRUE(study.claimKey("p1", "hash-1"));
  EXPECT_FALSE(study.claimKey("p1", "hash-2")) << "the first claim wins";
  EXPECT_EQ(study.keyHash("p1"), "hash-1");
  EXPECT_EQ(study.participantCount(), 1);
}

TEST_F(StudyRecordsTest, AWriterThatCannotGetTheLockFailsAsBusy) {
  StudyRecords study(path_, true, 100);
  study.begin("p1", 1, "{}");
  sqlite3* holder = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &holder), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(holder, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), SQLITE_OK);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(contains(errorOf([&] { study.record(page("p1", 0)); }), "busy"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_EQ(study.nextTrial("p1"), 0);  // readers are not blocked by a writer in WAL mode
  sqlite3_exec(holder, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(holder);
  EXPECT_EQ(study.record(page("p1", 0)).status, Status::Stored);
}

}  // namespace
}  // namespace cbtl::app::study
