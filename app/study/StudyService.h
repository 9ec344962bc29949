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
// Every request is checked completely before anything changes; a refused one changes nothing. Concurrency: the
// requests that touch a session run one at a time, whoever's they are, because every session plans with the one
// loaded program, which is not thread-safe (its built-ins are bound to the world being planned in); a page takes
// well under a second, and a participant minutes to answer it. The database has a lock of its own (taken inside
// that one, and alone by begin() and look-ups); the renderer and its workspace need none, as pictures are made
// under that one.
#pragma once

#include "app/profile/ProfileStore.h"
#include "app/study/StudyHttpServer.h"
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
  // Sessions kept at most (each holds two simulated worlds and a model, about 27 MB); beyond, the one used longest
  // ago is let go and rebuilt from the records when needed. A completed participant's is let go at once.
  std::size_t maxSessions = 64;
  // What the people running the study tell participants (StudyInfo.h), sent with every page's state as "study";
  // an empty object: the built-in consent text, no contact.
  nlohmann::json about = nlohmann::json::object();
  // One line per participant event (began, each page's answer stored or refused, finished), without the answers
  // themselves; called under no lock of the service's, from the request's thread. Null: nothing is logged.
  std::function<void(const std::string&)> log;
};

class StudyService : public StudyApi {
 public:
  // `lp` (the Feeding program) and `facts` must outlive the service. Opens (creating) the study database; throws
  // StudyError or profile::StoreError when it cannot. Pictures are rendered from the program's scene; when no
  // renderer can be made (no EGL here), they are answered 503 and pictureProblem() says why.
  StudyService(const approach::PreparedProgram& lp, const domains::ProgramFacts& facts, StudyServiceOptions options,
               const std::string& databasePath);
  ~StudyService() override;

  HttpReply begin(const std::string& participant) override;
  HttpReply state(const std::string& participant) override;
  HttpReply record(const std::string& participant, const std::string& body) override;  // logged (options.log)
  HttpReply view(const std::string& participant, int meal, int picture) override;
  HttpReply viewMeasure(const std::string& participant, int meal, int picture) override;

  const std::string& pictureProblem() const { return noRendererReason_; }
  // Sessions held in memory now (StudyServiceOptions::maxSessions).
  std::size_t sessionsInMemory();

 private:
  struct Session;
  // The stored participant, or the reply saying why there is none (400 for an invalid id, 404 for an unknown one).
  std::optional<HttpReply> lookUp(const std::string& participant, Participant& out);
  Session& sessionOf(const Participant& p);  // the caller holds programMutex_
  // The caller holds programMutex_ in these.
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

  const approach::PreparedProgram& lp_;
  const domains::ProgramFacts& facts_;
  StudyServiceOptions options_;
  std::mutex dbMutex_;
  StudyRecords records_;
  profile::ProfileStore profiles_;
  std::mutex programMutex_;  // over sessions_ and everything a session does
  std::map<std::string, std::unique_ptr<Session>> sessions_;
  std::uint64_t uses_ = 0;  // requests that touched a session, for letting the least recently used go
  std::shared_ptr<const world::Scene> scene_;
  std::unique_ptr<world::OffscreenRenderer> renderer_;
  std::unique_ptr<world::Workspace> pictureWorkspace_;
  std::string noRendererReason_;
};

}  // namespace cbtl::app::study
