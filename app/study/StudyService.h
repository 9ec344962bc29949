// StudyService.h — the paper's Feeding web study behind the HTTP API of docs/study-api.md: participants' sessions
// (domains/feeding/StudySession.h: CBTL and No Personalization, five meals, CBTL learning live from the answers),
// their pages' state, the checking and storing of each page's answer (StudyRecords), the learned model after each
// meal (a version of the participant's profile in the same file, source "study"), and the pictures of CBTL's
// configurations from the participant's eyes.
//
// Sessions: a participant's number (their simulated world's seed stream, FeedingStudy.h participantSeed) is the
// order in which they began, kept as the participant's seed. The study's seed and whether CBTL asks about its most
// uncertain view are kept with each participant when they begin, so a server restarted with other options still
// continues every participant as they started. A session is built when a participant is first seen after a start,
// by feeding their stored `answers` records to a fresh StudySession: StudySession is deterministic, so it shows
// the same meal they were at. The solver options and the text backend are the server's: restart a study with the
// same ones, or rebuilt sessions refuse (500, naming the participant) where the stored answers no longer fit.
//
// Every request is checked completely before anything changes; a refused one changes nothing. Concurrency: a
// session plans with a loaded copy of the program (a "planner"), which is not thread-safe (its built-ins are bound
// to the world being planned in), so the sessions of one planner plan one at a time; the service is given one
// planner per core (`cbtl study serve` loads the program that many times) and spreads participants over them, so
// that planning, and rebuilding a session let go, hold up only the planning of one planner's participants. A
// participant's requests take turns on their session's own lock; a request that does not plan (a page about no
// meal, a picture's measure, a rating) never waits for another participant's planning. Finding a participant's
// session takes a lock of its own for microseconds; a session in use is never let go. The database has a lock of its
// own (taken inside a planner's, and alone by begin() and look-ups); pictures are rendered under the renderer's own
// lock.
#pragma once

#include "app/profile/ProfileStore.h"
#include "app/study/StudyApi.h"
#include "app/study/StudyDatabaseLock.h"
#include "app/study/StudyRecords.h"
#include "domains/feeding/StudySession.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::world {
class OffscreenRenderer;
class Scene;
class Workspace;
}  // namespace cbtl::world

namespace cbtl::app::study {

struct StudyServiceOptions {
  domains::feeding::StudyOptions study;         // seed, exploring view, solver, text backend
  bool pictures = true;                         // false: no renderer (pictures are answered 503)
  int pictureWidth = 480, pictureHeight = 360;  // pixels
  // Sessions kept at most (each holds two simulated worlds and a model, about 24 MB: 256 are about 6 GB); beyond,
  // the idle one used longest ago is let go and rebuilt from the records when needed (0.2-1.4 s, holding up its
  // planner's participants). A completed participant's is let go at once.
  std::size_t maxSessions = 256;
  // What the people running the study tell participants (StudyInfo.h), sent with every page's state as "study";
  // an empty object: the built-in consent text, no contact.
  nlohmann::json about = nlohmann::json::object();
  // One line per participant event (began, each page's answer stored or refused, finished), without the answers
  // themselves; called under no lock of the service's, from the request's thread. Null: nothing is logged.
  std::function<void(const std::string&)> log;
};

class StudyService : public StudyApi {
 public:
  // `lp` (the Feeding program) and `facts` must outlive the service, and so must `morePlanners`: the same program
  // loaded again, one more planner each (they must be the very same program: a participant's pages must not depend
  // on the planner they get). With a language-model text backend only `lp` plans (a model client serves one thread).
  // Opens (creating) the study database and locks it to this service (StudyDatabaseLock.h); throws StudyError or
  // profile::StoreError when it cannot. Pictures are rendered from the program's scene; when no renderer can be
  // made (no EGL here), they are answered 503 and pictureProblem() says why.
  StudyService(const approach::PreparedProgram& lp, const domains::ProgramFacts& facts, StudyServiceOptions options,
               const std::string& databasePath, std::vector<const approach::PreparedProgram*> morePlanners = {});
  ~StudyService() override;

  HttpReply begin(const std::string& participant) override;
  HttpReply state(const std::string& participant) override;
  HttpReply record(const std::string& participant, const std::string& body) override;  // logged (options.log)
  HttpReply view(const std::string& participant, int meal, int picture) override;
  HttpReply viewMeasure(const std::string& participant, int meal, int picture) override;

  const std::string& pictureProblem() const { return noRendererReason_; }
  // Sessions held in memory now (StudyServiceOptions::maxSessions).
  std::size_t sessionsInMemory();
  std::size_t planners() const { return planners_.size(); }

 private:
  struct Session;
  struct Planner {
    const approach::PreparedProgram* program;
    std::mutex mutex;  // over the program, held while one of its sessions plans
  };
  class Lease;  // a participant's session, held for one request (StudyService.cpp)
  Lease lease(const Participant& p);
  // The stored participant, or the reply saying why there is none (400 for an invalid id, 404 for an unknown one).
  std::optional<HttpReply> lookUp(const std::string& participant, Participant& out);
  // The caller holds the session's Lease in these.
  std::optional<HttpReply> ensureBuilt(Session& s, const Participant& p);
  HttpReply stateReply(Session& s, const Participant& p, const char* status = nullptr);
  HttpReply storeAnswers(Session& s, const Participant& p, const NewRecord& r);
  HttpReply beginUnlogged(const std::string& participant);
  HttpReply recordUnlogged(const std::string& participant, const std::string& body);
  // options_.log's line for a request's reply: "P-1 began", "P-1 trial 3 (answers, meal 1): stored", "... 409: ...".
  void logReply(const std::string& participant, const std::string& what, const HttpReply& reply);
  void storeProfile(Session& s, const Participant& p, const std::vector<profile::NewEvent>& events, int meal);
  // Finds picture `picture` of meal `meal` of the participant's current meal and answers it with `answer` (called
  // with the session locked), or says why there is none.
  HttpReply withPicture(const std::string& participant, int meal, int picture,
                        const std::function<HttpReply(Session&, std::size_t)>& answer);
  HttpReply renderPicture(Session& s, std::size_t picture);

  const approach::PreparedProgram& lp_;  // the first planner's: the graph every planner shares
  const domains::ProgramFacts& facts_;
  StudyServiceOptions options_;
  std::mutex dbMutex_;
  StudyRecords records_;
  profile::ProfileStore profiles_;
  StudyDatabaseLock serverLock_;  // after the two above, which create the file
  std::vector<std::unique_ptr<Planner>> planners_;
  std::mutex sessionsMutex_;  // over sessions_, uses_ and each session's users and planner (not what it does)
  std::map<std::string, std::unique_ptr<Session>> sessions_;
  std::uint64_t uses_ = 0;  // requests that touched a session, for letting the least recently used go
  std::mutex renderMutex_;  // over renderer_ and pictureWorkspace_
  std::shared_ptr<const world::Scene> scene_;
  std::unique_ptr<world::OffscreenRenderer> renderer_;
  std::unique_ptr<world::Workspace> pictureWorkspace_;
  std::string noRendererReason_;
};

}  // namespace cbtl::app::study
