// The web study behind its API (app/study/StudyService.h, StudyPages.h) and over real HTTP (StudyHttpServer.h): a
// participant's thirteen pages with what is stored of each, a restart continuing every session where it was,
// replays, and bad requests refused without changing anything.
#include "app/study/StudyService.h"

#include "app/DomainSolverOptions.h"
#include "app/study/ParticipantAccess.h"
#include "app/study/StudyHttpServer.h"
#include "app/study/StudyInfo.h"
#include "app/study/StudyPages.h"
#include "app/study/StudyRecords.h"
#include "robot/world/PngWriter.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>
#include <thread>

namespace cbtl::app::study {
namespace {

using nlohmann::json;

const LoadedProgram& feedingProgram() {
  static const auto lp = LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  return *lp;
}

StudyServiceOptions serviceOptions(bool pictures = false) {
  StudyServiceOptions o;
  o.study.solver = domainSolverOptions("feeding");
  o.pictures = pictures;
  o.pictureWidth = 64;
  o.pictureHeight = 48;
  return o;
}

json body(const HttpReply& r) { return json::parse(r.body); }

// A StudyHttpServer answering on a free port of 127.0.0.1 until destroyed (also when an assertion returns early),
// with participants' keys checked over the study's database `db`.
struct ServerOnLoopback {
  ServerOnLoopback(StudyApi& api, const std::string& db, AdmissionOptions admission = {})
      : access(api, db, admission), server(access) {
    port = server.bind("127.0.0.1", 0, error);
    if (port > 0) listening = std::thread([this] { server.listen(); });
  }
  ~ServerOnLoopback() {
    if (!listening.joinable()) return;
    server.stop();
    listening.join();
  }
  ParticipantAccess access;
  StudyHttpServer server;
  std::string error;
  int port = -1;
  std::thread listening;
};

class StudyServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(feedingProgram().ok()) << feedingProgram().errors();
    dir_ = std::filesystem::temp_directory_path() /
           ("cbtl-serve-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir_);
    db_ = (dir_ / "study.sqlite").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::unique_ptr<StudyService> service(const std::string& db, bool pictures = false) {
    return std::make_unique<StudyService>(feedingProgram(), test::programFacts("feeding"), serviceOptions(pictures),
                                          db);
  }

  static json recordBody(std::int64_t trial, const std::string& kind, int meal, const json& response) {
    return {{"trial_index", trial},       {"kind", kind},         {"meal", meal},
            {"elapsed_ms", 1000 * trial}, {"rt_ms", 100 + trial}, {"response", response}};
  }

  // The answer this test's participant gives on `state`'s page: their ideals vary with the meal; Option A is
  // preferred on odd meals.
  static json answerFor(const json& state) {
    const std::string page = state["page"];
    const int meal = state["meal"];
    if (page == "consent") return {{"agree", true}};
    if (page == "demographics")
      return {{"age", 31},
              {"gender", "other"},
              {"gender_other", "agender"},
              {"robot_experience", true},
              {"fed_experience", false}};
    if (page == "rating") return {{"likert", meal % 2 == 1 ? 2 : 5}};
    if (page == "answers") {
      json blocked = json::array();
      // Odd meals: the first picture blocked (the one of CBTL's shown choice); even meals: the second.
      for (std::size_t k = 0; k < state["views"].size(); ++k) blocked.push_back(static_cast<int>(k) == (meal + 1) % 2);
      return {{"dip", state["choices"]["dip"][static_cast<std::size_t>(meal % 3)]},
              {"signal", meal < 3 ? "button" : "mouthOpen"},
              {"verbosity", "brief"},
              {"blocked", blocked}};
    }
    return {{"comments", "fine"}};
  }

  // Answers pages until the participant's next page is `untilPage` of meal `untilMeal` (or done); returns that state.
  static json answerUntil(StudyService& s, const std::string& id, json state, const std::string& untilPage,
                          int untilMeal) {
    while (state["page"] != "done" && !(state["page"] == untilPage && state["meal"] == untilMeal)) {
      const HttpReply r =
          s.record(id, recordBody(state["next_trial"], state["page"], state["meal"], answerFor(state)).dump());
      EXPECT_EQ(r.status, 200) << r.body;
      if (r.status != 200) return state;
      EXPECT_EQ(body(r)["status"], "stored");
      state = body(r)["state"];
    }
    return state;
  }

  std::filesystem::path dir_;
  std::string db_;
};

TEST_F(StudyServiceTest, AParticipantAnswersThirteenPagesAndTheRecordsKeepWhatEachPageShowed) {
  auto s = service(db_);
  HttpReply begun = s->begin("P-1");
  ASSERT_EQ(begun.status, 200) << begun.body;
  EXPECT_EQ(body(begun)["page"], "consent");
  EXPECT_EQ(body(begun)["next_trial"], 0);

  json state = body(begun);
  while (state["page"] != "done") {
    if (state["page"] == "rating" || state["page"] == "answers") {
      EXPECT_EQ(state["options"].size(), 2u);
      for (const auto& o : state["options"]) {
        EXPECT_FALSE(o.contains("approach")) << "the page must not say which";
      }
      EXPECT_EQ(state["choices"]["dip"].back(), "noDip");
      EXPECT_EQ(state["labels"]["noDip"], "no dip");
    }
    if (state["page"] == "answers") {
      EXPECT_EQ(state["views"].size(), 2u);
    }
    const HttpReply r =
        s->record("P-1", recordBody(state["next_trial"], state["page"], state["meal"], answerFor(state)).dump());
    ASSERT_EQ(r.status, 200) << r.body;
    state = body(r)["state"];
  }
  EXPECT_EQ(state["next_trial"], 13);
  EXPECT_EQ(body(s->state("P-1")), state) << "after the session was let go";
  EXPECT_EQ(s->record("P-1", recordBody(13, "complete", 0, {{"comments", ""}}).dump()).status, 409);

  StudyRecords records(db_, false);
  const auto stored = records.records("P-1");
  ASSERT_EQ(stored.size(), 13u);
  ASSERT_TRUE(records.participant("P-1")->completed.has_value());
  for (std::size_t t = 0; t < stored.size(); ++t) {
    const StudyPage page = pageOfTrial(static_cast<std::int64_t>(t));
    EXPECT_EQ(stored[t].kind, page.kind) << t;
    EXPECT_EQ(stored[t].meal, page.meal) << t;
    const json r = json::parse(stored[t].response);
    if (page.kind == "rating") {
      const int likert = r["likert"];
      EXPECT_EQ(likert, page.meal % 2 == 1 ? 2 : 5);
      const bool cbtlIsA = r["options"][0]["approach"] == "cbtl";
      EXPECT_EQ(r["cbtl_preference"], cbtlIsA ? 6 - likert : likert);
      EXPECT_NE(r["options"][0]["approach"], r["options"][1]["approach"]);
    }
    if (page.kind == "answers") {
      for (const char* q : {"dip", "signal", "verbosity"})
        for (const char* a : {"cbtl", "no-personalization"})
          EXPECT_EQ(r["met"][a][q], r["predicted"][a][q] == r[q]) << t << q << a;
      EXPECT_EQ(r["views"].size(), 2u);
      EXPECT_EQ(r["views"][0]["shown_choice"], true);
      EXPECT_EQ(r["met"]["cbtl"]["view"], page.meal % 2 == 0) << "met unless the shown choice's picture is blocked";
    }
  }
  profile::ProfileStore profiles(db_, false);
  const auto versions = profiles.versions("P-1", "feeding");
  ASSERT_EQ(versions.size(), 5u) << "one learned model per meal";
  EXPECT_EQ(versions.back().reason, "study: meal 5");
  const auto events = profiles.events("P-1", "feeding");
  ASSERT_FALSE(events.empty());
  for (const auto& e : events) EXPECT_EQ(e.source, profile::EventSource::Study);
}

TEST_F(StudyServiceTest, ARestartedServiceShowsWhatAnUninterruptedOneShows) {
  json uninterrupted;
  {
    auto s = service(db_);
    uninterrupted = answerUntil(*s, "P-2", body(s->begin("P-2")), "rating", 3);
  }
  const std::string db2 = (dir_ / "restarted.sqlite").string();
  {
    auto s = service(db2);
    answerUntil(*s, "P-2", body(s->begin("P-2")), "answers", 2);
  }
  auto restarted = service(db2);
  json state = body(restarted->state("P-2"));
  EXPECT_EQ(state["page"], "answers");
  EXPECT_EQ(state["meal"], 2);
  state = answerUntil(*restarted, "P-2", state, "rating", 3);
  EXPECT_EQ(state, uninterrupted);
  // A reload begins again: the same participant, the same page.
  EXPECT_EQ(body(restarted->begin("P-2")), uninterrupted);
}

TEST_F(StudyServiceTest, AProfileVersionLostToAKilledServerIsWrittenWhenTheSessionIsRebuilt) {
  // The records of a participant who answered meal 1, as a server that was killed before it stored the profile
  // version left them (the replay reads only the four answers of an answers record).
  {
    StudyRecords records(db_);
    records.begin("P-7", 0, R"({"study_seed": 0, "exploring_view": true})");
    const std::pair<const char*, const char*> pages[] = {
        {"consent", R"({"agree": true})"},
        {"demographics",
         R"({"age": null, "fed_experience": false, "gender": "male", "gender_other": "", "robot_experience": true})"},
        {"rating", R"({"likert": 3})"},
        {"answers", R"({"dip": "noDip", "signal": "button", "verbosity": "silent", "blocked": [false, false]})"}};
    for (std::int64_t t = 0; t < 4; ++t)
      records.record({"P-7", t, pages[t].first, t < 2 ? 0 : 1, 100 * t, 50, pages[t].second});
  }
  ASSERT_TRUE(profile::ProfileStore(db_).versions("P-7", "feeding").empty());
  auto s = service(db_);
  const json state = body(s->state("P-7"));
  EXPECT_EQ(state["page"], "rating");
  EXPECT_EQ(state["meal"], 2);
  const auto versions = profile::ProfileStore(db_).versions("P-7", "feeding");
  ASSERT_EQ(versions.size(), 1u);
  EXPECT_EQ(versions[0].reason, "study: meal 1");
  // Rebuilt again (another start), nothing is written twice.
  s.reset();
  auto again = service(db_);
  EXPECT_EQ(body(again->state("P-7")), state);
  EXPECT_EQ(profile::ProfileStore(db_).versions("P-7", "feeding").size(), 1u);
}

TEST_F(StudyServiceTest, SessionsBeyondTheCapAreLetGoAndRebuiltAsTheyWere) {
  StudyServiceOptions capped = serviceOptions();
  capped.maxSessions = 1;
  StudyService one(feedingProgram(), test::programFacts("feeding"), capped, db_);
  auto many = service((dir_ / "uncapped.sqlite").string());
  // Two participants taking turns: with a cap of one, each turn lets the other's session go, and it is rebuilt from
  // the records when they come back.
  json a = answerUntil(one, "P-8", body(one.begin("P-8")), "rating", 2);
  json b = answerUntil(one, "P-9", body(one.begin("P-9")), "answers", 2);
  a = answerUntil(one, "P-8", body(one.state("P-8")), "rating", 3);
  b = body(one.state("P-9"));
  EXPECT_EQ(one.sessionsInMemory(), 1u);
  const json a2 = answerUntil(*many, "P-8", body(many->begin("P-8")), "rating", 3);
  const json b2 = answerUntil(*many, "P-9", body(many->begin("P-9")), "answers", 2);
  EXPECT_EQ(a, a2);
  EXPECT_EQ(b, b2);
  EXPECT_EQ(many->sessionsInMemory(), 2u);
}

// Two planners (the program loaded twice) plan two participants at the same time, and each participant's pages are
// the ones a single planner shows them one after the other.
TEST_F(StudyServiceTest, TwoPlannersServeParticipantsAtOnceWithTheSamePages) {
  static const auto second = LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  ASSERT_TRUE(second->ok());
  StudyService two(feedingProgram(), test::programFacts("feeding"), serviceOptions(), db_, {second.get()});
  EXPECT_EQ(two.planners(), 2u);
  json begun[2] = {body(two.begin("P-14")), body(two.begin("P-15"))};
  json atOnce[2];
  std::thread other([&] { atOnce[1] = answerUntil(two, "P-15", begun[1], "rating", 4); });
  atOnce[0] = answerUntil(two, "P-14", begun[0], "rating", 4);
  other.join();
  auto one = service((dir_ / "one.sqlite").string());
  EXPECT_EQ(one->planners(), 1u);
  const json first = answerUntil(*one, "P-14", body(one->begin("P-14")), "rating", 4);
  const json then = answerUntil(*one, "P-15", body(one->begin("P-15")), "rating", 4);
  EXPECT_EQ(atOnce[0], first);
  EXPECT_EQ(atOnce[1], then);
}

TEST_F(StudyServiceTest, AResentRecordIsReplayedAndADifferentAnswerToAnAnsweredPageConflicts) {
  auto s = service(db_);
  json state = answerUntil(*s, "P-3", body(s->begin("P-3")), "answers", 1);
  const json rating = recordBody(2, "rating", 1, {{"likert", 2}});
  HttpReply again = s->record("P-3", rating.dump());
  ASSERT_EQ(again.status, 200) << again.body;
  EXPECT_EQ(body(again)["status"], "replayed");
  EXPECT_EQ(body(again)["state"], state);
  HttpReply other = s->record("P-3", recordBody(2, "rating", 1, {{"likert", 4}}).dump());
  EXPECT_EQ(other.status, 409);
  EXPECT_NE(body(other)["error"].get<std::string>().find("already answered"), std::string::npos) << other.body;
  EXPECT_EQ(body(other)["error"].get<std::string>().find("cbtl"), std::string::npos)
      << "a conflict must not say which option was CBTL: " << other.body;
  const json answers = recordBody(3, "answers", 1, answerFor(state));
  ASSERT_EQ(s->record("P-3", answers.dump()).status, 200);
  HttpReply replayedAnswers = s->record("P-3", answers.dump());
  EXPECT_EQ(replayedAnswers.status, 200) << replayedAnswers.body;
  EXPECT_EQ(body(replayedAnswers)["status"], "replayed");
  EXPECT_EQ(body(replayedAnswers)["state"]["meal"], 2) << "a replay does not answer the meal twice";
}

TEST_F(StudyServiceTest, BadRequestsAreRefusedWithAReasonAndChangeNothing) {
  auto s = service(db_);
  EXPECT_EQ(s->begin("no spaces").status, 400);
  EXPECT_EQ(s->state("unknown").status, 404);
  EXPECT_EQ(s->record("unknown", recordBody(0, "consent", 0, {{"agree", true}}).dump()).status, 404);
  const json atAnswers = answerUntil(*s, "P-4", body(s->begin("P-4")), "answers", 1);
  json wrongDip = answerFor(atAnswers);
  wrongDip["dip"] = "peanutButter";
  json tooFewViews = answerFor(atAnswers);
  tooFewViews["blocked"] = json::array({true});
  json extraField = answerFor(atAnswers);
  extraField["mood"] = "good";
  const struct {
    std::string body;
    int status;
    std::string says;
  } bad[] = {
      {"not json", 400, "not JSON"},
      {"[1, 2]", 400, "JSON object"},
      {json{{"trial_index", 3}, {"kind", "answers"}, {"meal", 1}}.dump(), 400, "elapsed_ms"},
      {recordBody(3, "answers", 1, wrongDip).dump(), 400, "peanutButter"},
      {recordBody(3, "answers", 1, tooFewViews).dump(), 400, "view"},
      {recordBody(3, "answers", 1, extraField).dump(), 400, "mood"},
      {recordBody(5, "answers", 2, answerFor(atAnswers)).dump(), 409, "next page"},
      {recordBody(3, "rating", 1, {{"likert", 3}}).dump(), 409, "'answers' page of meal 1"},
  };
  for (const auto& b : bad) {
    const HttpReply r = s->record("P-4", b.body);
    EXPECT_EQ(r.status, b.status) << b.body << " -> " << r.body;
    EXPECT_NE(body(r)["error"].get<std::string>().find(b.says), std::string::npos) << r.body;
  }
  EXPECT_EQ(body(s->state("P-4")), atAnswers) << "a refused request changed the session";
  EXPECT_EQ(StudyRecords(db_, false).nextTrial("P-4"), 3);
  const HttpReply right = s->record("P-4", recordBody(3, "answers", 1, answerFor(atAnswers)).dump());
  EXPECT_EQ(right.status, 200) << "the session still takes the right answers: " << right.body;
}

TEST_F(StudyServiceTest, PicturesAreTheCurrentMealsOnly) {
  auto s = service(db_, true);
  const json atAnswers = answerUntil(*s, "P-5", body(s->begin("P-5")), "answers", 1);
  EXPECT_EQ(s->view("P-5", 2, 0).status, 404) << "meal 2 is not shown yet";
  EXPECT_EQ(s->view("P-5", 1, 2).status, 404) << "two pictures only";
  const HttpReply picture = s->view("P-5", 1, 0);
  if (!s->pictureProblem().empty()) {
    EXPECT_EQ(picture.status, 503);
    EXPECT_EQ(body(picture)["error"], s->pictureProblem());
    return;
  }
  ASSERT_EQ(picture.status, 200) << picture.body;
  EXPECT_EQ(picture.contentType, "image/png");
  ASSERT_GT(picture.body.size(), 24u);
  EXPECT_EQ(picture.body.substr(1, 3), "PNG");
  // The width and height in the IHDR chunk, big-endian.
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(picture.body[at + i]);
    return v;
  };
  EXPECT_EQ(be32(16), 64u);
  EXPECT_EQ(be32(20), 48u);
  // The second picture through the server: rendered on one of its request threads, not the thread that made the
  // renderer (an OpenGL context is current in one thread at a time; a black picture would say it was not).
  std::optional<httplib::Result> second;
  {
    ServerOnLoopback loopback(*s, db_);
    ASSERT_GT(loopback.port, 0) << loopback.error;
    httplib::Client client("127.0.0.1", loopback.port);
    // P-5 began through the service, without a key: its first begin over HTTP issues one.
    auto begun = client.Post("/api/participants/P-5", "", "application/json");
    ASSERT_TRUE(begun);
    ASSERT_EQ(begun->status, 200) << begun->body;
    const std::string key = json::parse(begun->body)["key"];
    second = client.Get(atAnswers["views"][1].get<std::string>(), {{"Authorization", "Bearer " + key}});
  }
  ASSERT_TRUE(*second);
  const httplib::Response& viaServer = **second;
  ASSERT_EQ(viaServer.status, 200) << viaServer.body;
  EXPECT_NE(viaServer.body, picture.body) << "the two configurations look different";
  // A lit scene has mostly non-black pixels.
  const auto decoded = cbtl::world::decodePng(std::vector<std::uint8_t>(viaServer.body.begin(), viaServer.body.end()));
  ASSERT_TRUE(decoded.has_value());
  const auto lit = std::count_if(decoded->rgb.begin(), decoded->rgb.end(), [](std::uint8_t c) { return c != 0; });
  EXPECT_GT(lit, static_cast<std::ptrdiff_t>(decoded->rgb.size() / 4)) << "a black picture";
}

TEST_F(StudyServiceTest, TheHttpServerServesThePagesAndTheApiOnLoopback) {
  auto s = service(db_);
  ServerOnLoopback loopback(*s, db_);
  ASSERT_GT(loopback.port, 0) << loopback.error;
  const int port = loopback.port;
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(std::chrono::seconds(60));

  auto page = client.Get("/p/P-6");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("/static/study.js"), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'self'"), std::string::npos);
  for (const char* file : {"/static/study.js", "/static/study.css"}) {
    auto f = client.Get(file);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->status, 200) << file;
    EXPECT_FALSE(f->body.empty());
  }
  auto fromRecruiter = client.Get("/?PROLIFIC_PID=5f3a9c&STUDY_ID=x");
  ASSERT_TRUE(fromRecruiter);
  EXPECT_EQ(fromRecruiter->status, 302);
  EXPECT_EQ(fromRecruiter->get_header_value("Location"), "/p/5f3a9c");
  auto badFromRecruiter = client.Get("/?participant=a%20b");
  ASSERT_TRUE(badFromRecruiter);
  EXPECT_EQ(badFromRecruiter->status, 400);
  auto missing = client.Get("/static/other.js");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_TRUE(json::parse(missing->body).contains("error"));

  auto begun = client.Post("/api/participants/P-6", "", "application/json");
  ASSERT_TRUE(begun);
  EXPECT_EQ(begun->status, 200);
  EXPECT_EQ(json::parse(begun->body)["page"], "consent");
  const std::string key = json::parse(begun->body).value("key", "");
  EXPECT_EQ(key.size(), 64u) << begun->body;
  const httplib::Headers withKey = {{"Authorization", "Bearer " + key}};
  auto consent = client.Post("/api/participants/P-6/records", withKey,
                             recordBody(0, "consent", 0, {{"agree", true}}).dump(), "application/json");
  ASSERT_TRUE(consent);
  EXPECT_EQ(consent->status, 200) << consent->body;
  EXPECT_EQ(json::parse(consent->body)["state"]["page"], "demographics");
  auto tooLarge =
      client.Post("/api/participants/P-6/records", withKey, std::string(100 * 1024, ' '), "application/json");
  ASSERT_TRUE(tooLarge);
  EXPECT_EQ(tooLarge->status, 413);
  auto badId = client.Get("/api/participants/a%20b");
  ASSERT_TRUE(badId);
  EXPECT_EQ(badId->status, 400);
  // A second server cannot take a port the first one listens on (it would share its connections).
  StudyHttpServer second(loopback.access);
  std::string error;
  EXPECT_EQ(second.bind("127.0.0.1", port, error), -1);
  EXPECT_NE(error.find("cannot listen"), std::string::npos) << error;
}

// Nobody acts as a participant without their key: not by knowing or guessing the id, not from another site, not with
// a form; and the answers are never read back.
TEST_F(StudyServiceTest, ParticipantsActOnlyWithTheirKeyAndOnlyFromTheStudysPages) {
  auto s = service(db_);
  ServerOnLoopback loopback(*s, db_);
  ASSERT_GT(loopback.port, 0) << loopback.error;
  httplib::Client client("127.0.0.1", loopback.port);
  client.set_read_timeout(std::chrono::seconds(60));
  auto begun = client.Post("/api/participants/P-10", "", "application/json");
  ASSERT_TRUE(begun);
  ASSERT_EQ(begun->status, 200) << begun->body;
  const std::string key = json::parse(begun->body)["key"];
  const httplib::Headers withKey = {{"Authorization", "Bearer " + key}};
  const std::string consent = recordBody(0, "consent", 0, {{"agree", true}}).dump();
  // Without the key, with another, with another participant's: 403, the same words for a known and an unknown id.
  auto other = client.Post("/api/participants/P-11", "", "application/json");
  ASSERT_TRUE(other);
  const std::string otherKey = json::parse(other->body)["key"];
  std::string refusal;
  for (const auto& [path, headers] : std::vector<std::pair<std::string, httplib::Headers>>{
           {"/api/participants/P-10", {}},
           {"/api/participants/P-10", {{"Authorization", "Bearer " + std::string(64, '0')}}},
           {"/api/participants/P-10", {{"Authorization", "Bearer " + otherKey}}},
           {"/api/participants/P-10", {{"Authorization", key}}},
           {"/api/participants/nobody", {}},
           {"/api/participants/nobody", withKey},
           {"/api/participants/P-10/views/1/0.json", {}}}) {
    auto r = client.Get(path, headers);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << path << ": " << r->body;
    if (refusal.empty()) refusal = r->body;
    EXPECT_EQ(r->body, refusal) << path;
  }
  auto noKeyRecord = client.Post("/api/participants/P-10/records", consent, "application/json");
  ASSERT_TRUE(noKeyRecord);
  EXPECT_EQ(noKeyRecord->status, 403);
  // A second begin without the key does not hand out a key to a participant who has one.
  auto again = client.Post("/api/participants/P-10", "", "application/json");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 403);
  EXPECT_FALSE(json::parse(again->body).contains("key"));
  auto continued = client.Post("/api/participants/P-10", withKey, "", "application/json");
  ASSERT_TRUE(continued);
  EXPECT_EQ(continued->status, 200);
  EXPECT_FALSE(json::parse(continued->body).contains("key")) << "a key is sent once";
  // Not JSON (what a cross-site form sends), or from another site: refused, nothing stored.
  auto form = client.Post("/api/participants/P-10/records", withKey, consent, "text/plain");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 415) << form->body;
  httplib::Headers elsewhere = withKey;
  elsewhere.emplace("Origin", "https://attacker.example");
  auto crossSite = client.Post("/api/participants/P-10/records", elsewhere, consent, "application/json");
  ASSERT_TRUE(crossSite);
  EXPECT_EQ(crossSite->status, 403) << crossSite->body;
  httplib::Headers fetchMetadata = withKey;
  fetchMetadata.emplace("Sec-Fetch-Site", "cross-site");
  auto crossSiteFetch = client.Post("/api/participants/P-10/records", fetchMetadata, consent, "application/json");
  ASSERT_TRUE(crossSiteFetch);
  EXPECT_EQ(crossSiteFetch->status, 403);
  EXPECT_EQ(StudyRecords(db_, false).nextTrial("P-10"), 0) << "a refused request stored an answer";
  // From the study's own page (its Origin is the Host it talks to): taken.
  httplib::Headers samePage = withKey;
  samePage.emplace("Origin", "http://127.0.0.1:" + std::to_string(loopback.port));
  auto fromPage = client.Post("/api/participants/P-10/records", samePage, consent, "application/json");
  ASSERT_TRUE(fromPage);
  EXPECT_EQ(fromPage->status, 200) << fromPage->body;
  // The database keeps a hash of the key, never the key.
  EXPECT_EQ(StudyRecords(db_, false).keyHash("P-10"), participantKeyHash(key));
}

// A different answer to an answered page is refused without quoting what is stored (an age, a self-described gender).
TEST_F(StudyServiceTest, AConflictNeverQuotesTheStoredAnswer) {
  auto s = service(db_);
  answerUntil(*s, "P-12", body(s->begin("P-12")), "rating", 1);
  const json changed = recordBody(1, "demographics", 0,
                                  {{"age", 45},
                                   {"gender", "female"},
                                   {"gender_other", ""},
                                   {"robot_experience", false},
                                   {"fed_experience", false}});
  const HttpReply r = s->record("P-12", changed.dump());
  EXPECT_EQ(r.status, 409);
  EXPECT_EQ(r.body.find("agender"), std::string::npos) << r.body;
  EXPECT_EQ(r.body.find("31"), std::string::npos) << r.body;
}

// New participants are admitted at a bounded rate and up to a bounded number; trying ids counts too.
TEST_F(StudyServiceTest, NewParticipantsAreAdmittedAtABoundedRateAndNumber) {
  auto s = service(db_);
  ParticipantAccess access(*s, db_, AdmissionOptions{60, 2, 3});
  auto now = std::chrono::steady_clock::time_point{};
  access.setClock([&] { return now; });
  EXPECT_EQ(access.begin("A-1", "").status, 200);
  EXPECT_EQ(access.begin("A-2", "").status, 200);
  const HttpReply tooFast = access.begin("A-3", "");
  EXPECT_EQ(tooFast.status, 429) << tooFast.body;
  EXPECT_EQ(tooFast.retryAfterSeconds, 1);
  EXPECT_EQ(access.begin("A-1", "").status, 429) << "trying a known id without its key is counted as well";
  now += std::chrono::seconds(1);
  EXPECT_EQ(access.begin("A-3", "").status, 200);
  now += std::chrono::seconds(10);
  const HttpReply full = access.begin("A-4", "");
  EXPECT_EQ(full.status, 403);
  EXPECT_NE(full.body.find("all the participants"), std::string::npos) << full.body;
  EXPECT_EQ(StudyRecords(db_, false).participantCount(), 3);
}

TEST(AdmissionLimit, RefillsAtItsRateUpToItsBurst) {
  AdmissionLimit limit(AdmissionOptions{30, 2, 0});
  auto t = std::chrono::steady_clock::time_point{};
  EXPECT_EQ(limit.admit(t, 0).verdict, AdmissionLimit::Verdict::Admitted);
  EXPECT_EQ(limit.admit(t, 0).verdict, AdmissionLimit::Verdict::Admitted);
  const AdmissionLimit::Decision d = limit.admit(t, 0);
  EXPECT_EQ(d.verdict, AdmissionLimit::Verdict::TooFast);
  EXPECT_EQ(d.retryAfterSeconds, 2);
  t += std::chrono::hours(1);  // the bucket holds at most its burst
  EXPECT_EQ(limit.admit(t, 0).verdict, AdmissionLimit::Verdict::Admitted);
  EXPECT_EQ(limit.admit(t, 0).verdict, AdmissionLimit::Verdict::Admitted);
  EXPECT_EQ(limit.admit(t, 0).verdict, AdmissionLimit::Verdict::TooFast);
  EXPECT_EQ(AdmissionLimit(AdmissionOptions{0, 0, 5}).admit(t, 5).verdict, AdmissionLimit::Verdict::Full);
  EXPECT_EQ(AdmissionLimit(AdmissionOptions{0, 0, 0}).admit(t, 1000000).verdict, AdmissionLimit::Verdict::Admitted);
}

// One server per database: a second service on it is refused while the first runs, and takes it after.
TEST_F(StudyServiceTest, ASecondServerOnTheSameDatabaseIsRefused) {
  {
    auto first = service(db_);
    try {
      auto second = service(db_);
      ADD_FAILURE() << "two services on one database";
    } catch (const StudyError& e) {
      EXPECT_NE(std::string(e.what()).find("another study server is using this database"), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(first->begin("P-13").status, 200);
  }
  EXPECT_NO_THROW(service(db_));
}

}  // namespace
}  // namespace cbtl::app::study

// gender_other is required only with the gender "other"; elsewhere it may be left out or be empty.
TEST(StudyPages, GenderOtherIsOnlyRequiredForTheGenderOther) {
  const auto demographics = [](nlohmann::json extra) {
    nlohmann::json r = {{"age", nullptr}, {"gender", "female"}, {"robot_experience", false}, {"fed_experience", true}};
    r.update(extra);
    return cbtl::app::study::checkResponse("demographics", r);
  };
  EXPECT_FALSE(demographics(nlohmann::json::object()).has_value());
  EXPECT_FALSE(demographics({{"gender_other", ""}}).has_value());
  EXPECT_TRUE(demographics({{"gender_other", "x"}}).has_value());
  EXPECT_FALSE(demographics({{"gender", "other"}, {"gender_other", "agender"}}).has_value());
  const auto missing = demographics({{"gender", "other"}});
  ASSERT_TRUE(missing.has_value());
  EXPECT_NE(missing->find("gender_other"), std::string::npos) << *missing;
}

// Text fields are as long as the page lets them be: counted in UTF-16 units, as a browser's maxlength counts, not in
// UTF-8 bytes (100 letters of Greek are 200 bytes; an emoji is two units).
TEST(StudyPages, TextLimitsCountAsThePageCounts) {
  const auto other = [](const std::string& text) {
    return cbtl::app::study::checkResponse("demographics", {{"age", nullptr},
                                                            {"gender", "other"},
                                                            {"gender_other", text},
                                                            {"robot_experience", false},
                                                            {"fed_experience", true}});
  };
  std::string greek, emoji, hanzi;
  for (int i = 0; i < 100; ++i) greek += "\u03b1";     // 2 bytes, 1 unit
  for (int i = 0; i < 50; ++i) emoji += "\U0001F600";  // 4 bytes, 2 units
  for (int i = 0; i < 2000; ++i) hanzi += "\u5b57";    // 3 bytes, 1 unit
  EXPECT_FALSE(other(greek).has_value()) << *other(greek);
  EXPECT_FALSE(other(emoji).has_value());
  EXPECT_TRUE(other(greek + "\u03b1").has_value());
  EXPECT_TRUE(other(emoji + "a").has_value()) << "51 emoji are 102 units";
  EXPECT_FALSE(cbtl::app::study::checkResponse("complete", {{"comments", hanzi}}).has_value());
  EXPECT_TRUE(cbtl::app::study::checkResponse("complete", {{"comments", hanzi + "x"}}).has_value());
}

// The study-info file: every field optional, texts only, an unknown field named (a typo would vanish otherwise).
TEST(StudyInfo, FieldsAreCheckedAndUnknownOnesNamed) {
  using cbtl::app::study::checkStudyInfo;
  using cbtl::app::study::StudyInfoError;
  const nlohmann::json good = {{"title", "Feeding study"},
                               {"researcher", "Dr. A"},
                               {"contact", "a@example.org"},
                               {"ethics_approval", "IRB-1"},
                               {"consent", {"One.", "Two."}}};
  EXPECT_EQ(checkStudyInfo(good, "info.json"), good);
  EXPECT_EQ(checkStudyInfo(nlohmann::json::object(), "info.json"), nlohmann::json::object());
  const auto message = [](const nlohmann::json& j) {
    try {
      checkStudyInfo(j, "info.json");
    } catch (const StudyInfoError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"ethics", "IRB-1"}}).find("unknown field \"ethics\""), std::string::npos);
  EXPECT_NE(message({{"title", 3}}).find("\"title\" must be a text"), std::string::npos);
  EXPECT_NE(message({{"consent", "one paragraph"}}).find("list of 1 to 20 paragraphs"), std::string::npos);
  EXPECT_NE(message({{"consent", {"ok", 5}}}).find("paragraph 2 must be a text"), std::string::npos);
  EXPECT_NE(message({{"contact", std::string(2001, 'x')}}).find("longer than 2000"), std::string::npos);
  EXPECT_NE(message(nlohmann::json::array()).find("one JSON object"), std::string::npos);
}
