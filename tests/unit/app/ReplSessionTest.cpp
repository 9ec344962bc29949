#include "app/repl/ReplSession.h"

#include "app/DomainSolverOptions.h"
#include "app/profile/ProfileStore.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <unistd.h>

using namespace cbtl;
using cbtl::app::repl::ReplSession;

namespace {

// A session over Cooking whose output is captured in memory.
class Session {
 public:
  explicit Session(std::atomic<bool>* interrupt = nullptr, std::shared_ptr<app::profile::ProfileStore> store = {},
                   const std::string& user = {}) {
    out_ = open_memstream(&buffer_, &size_);
    app::repl::ReplConfig config;
    config.solverOptions = [](const std::string& domain) { return app::domainSolverOptions(domain); };
    config.interrupt = interrupt;
    config.store = std::move(store);
    config.user = user;
    session_ = std::make_unique<ReplSession>(config, out_);
  }
  ~Session() {
    session_.reset();
    std::fclose(out_);
    std::free(buffer_);
  }
  // Runs `input` and returns what it printed.
  std::string run(const std::string& input, ReplSession::Outcome expected = ReplSession::Outcome::Ok) {
    const std::size_t before = (std::fflush(out_), size_);
    EXPECT_EQ(session_->execute(input), expected) << input;
    std::fflush(out_);
    return std::string(buffer_ + before, size_ - before);
  }
  ReplSession& operator*() { return *session_; }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* out_ = nullptr;
  std::unique_ptr<ReplSession> session_;
};

const std::string kCooking = std::string(CBTL_DOMAINS_DIR) + "/cooking/cooking.cbtl";

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(ReplSession, UndoRestoresTheModelExactly) {
  const auto dir = std::filesystem::temp_directory_path() / ("cbtl-repl-undo-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  Session s;
  s.run("load " + kCooking);
  s.run("profile save " + (dir / "before.json").string());
  s.run("feedback mealCritique(seasoning, salt, 3, 31, 0.9, wantHotter, wantMore)");
  EXPECT_NE(s.run("learn").find("learned 2 labels from 1 event"), std::string::npos);
  s.run("profile save " + (dir / "learned.json").string());
  EXPECT_NE(slurp(dir / "before.json"), slurp(dir / "learned.json"));
  s.run("undo");
  s.run("profile save " + (dir / "after.json").string());
  EXPECT_EQ(slurp(dir / "before.json"), slurp(dir / "after.json"));
  s.run("undo", ReplSession::Outcome::Failed);
  // A profile load is undone the same way.
  s.run("profile load " + (dir / "learned.json").string());
  s.run("undo");
  s.run("profile save " + (dir / "after-load.json").string());
  EXPECT_EQ(slurp(dir / "before.json"), slurp(dir / "after-load.json"));
  std::filesystem::remove_all(dir);
}

TEST(ReplSession, ActQueuesTheSimulatedUsersFeedback) {
  Session s;
  s.run("load " + kCooking);
  s.run("act", ReplSession::Outcome::Failed);  // nothing solved yet
  EXPECT_NE(s.run("solve").find("status: solved"), std::string::npos);
  const std::string acted = s.run("act");
  EXPECT_NE(acted.find("the user: mealCritique("), std::string::npos) << acted;
  EXPECT_NE(s.run("show feedback").find("[simulated user]"), std::string::npos);
  s.run("act", ReplSession::Outcome::Failed);  // a plan is carried out once
  EXPECT_NE(s.run("learn").find("labels in the model"), std::string::npos);
  s.run("learn", ReplSession::Outcome::Failed);
}

TEST(ReplSession, AnInterruptStopsTheSolveWithoutAPlan) {
  std::atomic<bool> interrupt{false};
  Session s(&interrupt);
  s.run("load " + kCooking);
  // execute() clears a Ctrl-C pressed at the prompt, so the flag is raised from inside the command: the solver's
  // first iteration sees it only if it is still set, which a second thread guarantees here.
  std::atomic<bool> stop{false};
  std::thread raiser([&] {
    while (!stop.load()) interrupt.store(true);
  });
  for (const char* ing : {"salt", "pepper", "sugar", "flour"}) s.run(std::string("observe stock[") + ing + "] = 0");
  const std::string out = s.run("solve");
  stop.store(true);
  raiser.join();
  EXPECT_NE(out.find("status: interrupted"), std::string::npos) << out;
  EXPECT_EQ(out.find("plan ("), std::string::npos);
  EXPECT_NE(s.run("observe simulator").find("a new cooking world"), std::string::npos);
}

// A robot domain solves in dry-run tiers: an interrupted one reports no tier after it as "failed", since they never
// ran.
TEST(ReplSession, AnInterruptedRobotSolveReportsNoTierThatNeverRan) {
  std::atomic<bool> interrupt{false};
  Session s(&interrupt);
  s.run("load " + std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  std::atomic<bool> stop{false};
  std::thread raiser([&] {
    while (!stop.load()) interrupt.store(true);
  });
  const std::string out = s.run("solve");
  stop.store(true);
  raiser.join();
  EXPECT_NE(out.find("status: interrupted"), std::string::npos) << out;
  EXPECT_EQ(out.find("dry-run tier with"), std::string::npos) << out;
  EXPECT_EQ(out.find("replanned"), std::string::npos) << out;
}

TEST(ReplSession, CompletionOffersCommandsAndTheProgramsNames) {
  Session s;
  EXPECT_EQ((*s).completions("li"), std::vector<std::string>{"list"});
  EXPECT_EQ((*s).completions("re"), (std::vector<std::string>{"reload", "reset"}));
  EXPECT_EQ((*s).completions("list ta"), std::vector<std::string>{"tasks"});
  s.run("load " + kCooking);
  EXPECT_EQ((*s).completions("observe stock[s"), (std::vector<std::string>{"stock[salt]", "stock[sugar]"}));
  EXPECT_EQ((*s).completions("feedback mealC"), std::vector<std::string>{"mealCritique("});
  EXPECT_EQ((*s).completions("feedback mealCritique(seasoning, salt, 3, 31, 0.9, wantH"),
            std::vector<std::string>{"wantHotter"});
  EXPECT_EQ((*s).completions("solve h"), std::vector<std::string>{"hard"});
  EXPECT_EQ((*s).completions(":eval quantity[salt] + qu"), std::vector<std::string>{"quantity"});
  EXPECT_EQ((*s).completions(":eval st"), (std::vector<std::string>{"startTick", "stock"}));
  EXPECT_EQ((*s).completions(":ev"), std::vector<std::string>{":eval"});
  // After `NAME =`, only the values of NAME's type: a Pot's members, a bool's, nothing for a number.
  EXPECT_EQ((*s).completions("why-not pot[salt] = p"), (std::vector<std::string>{"pot0", "pot1", "pot2", "pot3"}));
  EXPECT_EQ((*s).completions("why-not used[salt] = "), (std::vector<std::string>{"false", "true"}));
  EXPECT_EQ((*s).completions("why-not pot[salt]=no"), std::vector<std::string>{"noPot"});
  EXPECT_TRUE((*s).completions("observe stock[salt] = ").empty()) << "a real has no values to offer";
}

TEST(ReplSession, UnfinishedInputContinues) {
  EXPECT_TRUE(ReplSession::needsMoreInput("feedback mealCritique(seasoning,"));
  EXPECT_TRUE(ReplSession::needsMoreInput("observe x = \"open ("));
  EXPECT_TRUE(ReplSession::needsMoreInput("solve \\"));
  EXPECT_FALSE(ReplSession::needsMoreInput("observe x = \"(\""));
  EXPECT_FALSE(ReplSession::needsMoreInput("feedback f(a, (1, 2))"));
}

// Another process storing learning while a REPL session has the profile loaded: the session's next learn would
// drop that learning, so it is refused with the feedback kept; loading the program again starts from the new head.
TEST(ReplSession, ALearnOverAnotherProcesssVersionIsRefusedAndTheFeedbackKept) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("cbtl-repl-store-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "profiles.sqlite").string();
  auto store = std::make_shared<app::profile::ProfileStore>(db);
  Session s(nullptr, store, "ann");
  s.run("load " + kCooking);
  s.run("feedback mealCritique(seasoning, salt, 3, 31, 0.9, wantHotter, wantMore)");
  EXPECT_NE(s.run("learn").find("stored as version 1"), std::string::npos);
  {
    app::profile::ProfileStore other(db, false);
    const auto head = other.head("ann", "cooking");
    other.recordLearning("ann", "cooking", {}, head->model, head->labels, "learn", 1);
  }
  s.run("feedback mealCritique(seasoning, pepper, 3, 31, 0.9, wantHotter, wantMore)");
  const std::string refused = s.run("learn", ReplSession::Outcome::Failed);
  EXPECT_NE(refused.find("changed while this model was learned"), std::string::npos) << refused;
  EXPECT_NE(refused.find("the feedback stays queued"), std::string::npos) << refused;
  EXPECT_EQ(store->head("ann", "cooking")->version, 2);
  EXPECT_NE(s.run("load " + kCooking).find("version 2"), std::string::npos);
  s.run("feedback mealCritique(seasoning, pepper, 3, 31, 0.9, wantHotter, wantMore)");
  EXPECT_NE(s.run("learn").find("stored as version 3"), std::string::npos);
  std::filesystem::remove_all(dir);
}
