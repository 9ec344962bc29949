#include "app/study/StudyService.h"

#include "app/PlanReport.h"
#include "app/study/StudyPages.h"
#include "domains/feeding/BiteAnswers.h"
#include "robot/world/PngWriter.h"
#include "robot/world/Renderer.h"
#include "robot/world/Workspace.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdio>

namespace cbtl::app::study {

namespace feeding = domains::feeding;
using nlohmann::json;

struct StudyService::Session {
  std::unique_ptr<feeding::StudySession> study;  // null until built
  std::string broken;                            // why it could not be built or continued; empty when fine
  std::size_t picturesMeal = static_cast<std::size_t>(-1);
  std::vector<std::vector<std::uint8_t>> pictures;  // the current meal's, PNG bytes, rendered on first request
  std::mutex mutex;                                 // held by the request that has the session (Lease)
  // Under StudyService::sessionsMutex_:
  Planner* planner = nullptr;  // for life: the session's worlds are bound to its program
  std::uint64_t lastUse = 0;   // StudyService::uses_ when a request last touched it
  int users = 0;               // requests holding a Lease on it: never let go while > 0
  bool finished = false;       // the participant completed: let go when the last user is done
};

// A participant's session for the length of one request: counted as in use, so that it is not let go meanwhile,
// and locked, so that the participant's requests take turns. Planning takes the planner's lock besides (planning()),
// only while it plans: a request that only reads the session (a picture's measure, a page about no meal) does not
// wait for another participant's planning.
class StudyService::Lease {
 public:
  Lease(StudyService& service, Session& session) : service_(service), session_(session), lock_(session.mutex) {}
  ~Lease() {
    lock_.unlock();
    std::lock_guard<std::mutex> lock(service_.sessionsMutex_);
    if (--session_.users == 0 && session_.finished) {
      // A finished participant's two worlds and learner are not needed any more (tens of MB); a later request
      // rebuilds them from the records.
      for (auto it = service_.sessions_.begin(); it != service_.sessions_.end(); ++it)
        if (it->second.get() == &session_) {
          service_.sessions_.erase(it);
          break;
        }
    }
  }
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;

  Session& session() { return session_; }

 private:
  StudyService& service_;
  Session& session_;
  std::unique_lock<std::mutex> lock_;
};

namespace {

// A value for the log: JSON text (a hostile value cannot forge a line), invalid UTF-8 replaced, at most 200 bytes.
std::string logText(const json& value) {
  std::string text = value.dump(-1, ' ', true, json::error_handler_t::replace);
  if (text.size() > 200) text = text.substr(0, 200) + "...";
  return text;
}

HttpReply jsonReply(const json& j, int status = 200) {
  return HttpReply{status, "application/json", j.dump(-1, ' ', false, json::error_handler_t::replace)};
}

// A StudyRecords failure after every check passed: the database's (busy, broken), not the request's.
HttpReply storageError(const std::exception& e) {
  const std::string what = e.what();
  return errorReply(what.find("busy") != std::string::npos ? 503 : 500, what);
}

}  // namespace

StudyService::StudyService(const approach::PreparedProgram& lp, const domains::ProgramFacts& facts,
                           StudyServiceOptions options, const std::string& databasePath,
                           std::vector<const approach::PreparedProgram*> morePlanners)
    : lp_(lp),
      facts_(facts),
      options_(std::move(options)),
      records_(databasePath),
      profiles_(databasePath),
      serverLock_(databasePath) {
  planners_.push_back(std::make_unique<Planner>());
  planners_.back()->program = &lp;
  if (!options_.study.textBackend)
    for (const approach::PreparedProgram* more : morePlanners) {
      planners_.push_back(std::make_unique<Planner>());
      planners_.back()->program = more;
    }
  if (!options_.pictures) {
    noRendererReason_ = "this server was started without pictures";
    return;
  }
  scene_ = facts.scene;
  if (!scene_) {
    auto loaded = world::Scene::loadFile(facts.scenePath);
    scene_ = loaded.scene;
    if (!scene_) {
      noRendererReason_ = "the program's scene could not be loaded: " + facts.scenePath;
      return;
    }
  }
  world::RenderStatus status{};
  std::string message;
  renderer_ = world::OffscreenRenderer::create(scene_, status, message);
  if (!renderer_) {
    noRendererReason_ = fmt::format("pictures cannot be rendered here: {}: {}", world::toString(status), message);
    return;
  }
  pictureWorkspace_ = std::make_unique<world::Workspace>(scene_);
}

StudyService::~StudyService() = default;

std::size_t StudyService::sessionsInMemory() {
  std::lock_guard<std::mutex> lock(sessionsMutex_);
  return sessions_.size();
}

StudyService::Lease StudyService::lease(const Participant& p) {
  Session* session = nullptr;
  {
    std::lock_guard<std::mutex> lock(sessionsMutex_);
    auto& slot = sessions_[p.id];
    if (!slot) {
      slot = std::make_unique<Session>();
      // By the participant's number, so that participants who begin one after another alternate.
      slot->planner = planners_[p.seed % planners_.size()].get();
    }
    slot->lastUse = ++uses_;
    slot->finished = false;
    ++slot->users;
    session = slot.get();
    // Over the cap, the idle session touched longest ago is let go (it is rebuilt from the records when its
    // participant comes back). One in use is never let go: the cap may be passed while every session is in use.
    if (sessions_.size() > options_.maxSessions) {
      auto oldest = sessions_.end();
      for (auto it = sessions_.begin(); it != sessions_.end(); ++it)
        if (it->second->users == 0 && (oldest == sessions_.end() || it->second->lastUse < oldest->second->lastUse))
          oldest = it;
      if (oldest != sessions_.end()) sessions_.erase(oldest);
    }
  }
  return Lease(*this, *session);
}

namespace {

// What CBTL learns from a meal's answers, in words, for the participant's profile (the session learns the same
// events: FeedingStudy.h answerMeal).
std::vector<profile::NewEvent> profileEvents(const feeding::MealPresentation& m,
                                             const feeding::ParticipantAnswers& answers,
                                             const ir::ConstraintGraph& graph) {
  std::vector<profile::NewEvent> events;
  const feeding::MealOffer& cbtl = m.offers.at(feeding::studyApproaches()[0]);
  const feeding::Meal& meal = feeding::paperMeals().at(m.meal);
  if (cbtl.shown.ok)
    for (const auto& e : feeding::biteAnswerEvents(
             feeding::BiteOffer{meal.food, meal.dips, cbtl.read.dip, cbtl.read.signal, cbtl.read.verbosity},
             answers.ideals))
      events.push_back({profile::EventSource::Study, renderEvent(e, &graph), ""});
  for (std::size_t k = 0; k < m.views.size() && k < answers.blocked.size(); ++k)
    events.push_back({profile::EventSource::Study,
                      renderEvent(feeding::viewAnswerEvent(m.views[k].conf, answers.blocked[k]), &graph), ""});
  return events;
}

// The participant's own study options (kept when they began) over the server's.
feeding::StudyOptions optionsOf(const Participant& p, feeding::StudyOptions base) {
  const json o = json::parse(p.options, nullptr, false);
  if (o.is_object()) {
    if (o.contains("study_seed") && o["study_seed"].is_number_unsigned()) base.seed = o["study_seed"];
    if (o.contains("exploring_view") && o["exploring_view"].is_boolean()) base.askExploringView = o["exploring_view"];
  }
  return base;
}

}  // namespace

namespace {

// The lock of the program `planner` plans with; the caller holds a session's Lease. Taken around everything that
// plans: building or replaying a session, answering a meal, and presenting the next one (StudySession::current()
// plans it on its first call, so every planning step ends by calling it, and later calls only read).
std::unique_lock<std::mutex> planning(std::mutex& planner) { return std::unique_lock<std::mutex>(planner); }

}  // namespace

std::optional<HttpReply> StudyService::ensureBuilt(Session& s, const Participant& p) {
  if (!s.study && s.broken.empty()) {
    const auto plans = planning(s.planner->mutex);
    std::vector<StoredRecord> stored;
    std::size_t profileVersions = 0;
    {
      std::lock_guard<std::mutex> lock(dbMutex_);
      stored = records_.records(p.id);
      profileVersions = profiles_.versions(p.id, lp_.graph().domain).size();
    }
    try {
      // StudySession is deterministic: fed the stored answers, it shows the meal the participant is at.
      s.study = std::make_unique<feeding::StudySession>(*s.planner->program, facts_, optionsOf(p, options_.study),
                                                        static_cast<int>(p.seed));
      for (const StoredRecord& r : stored) {
        if (r.kind != "answers") continue;
        const feeding::ParticipantAnswers a = participantAnswersOf(json::parse(r.response));
        if (auto problem = s.study->check(a))
          throw std::runtime_error(fmt::format("trial {} (meal {}): {}", r.trialIndex, r.meal, *problem));
        const std::vector<profile::NewEvent> events = profileEvents(s.study->current(), a, lp_.graph());
        s.study->answer(a);
        // A server stopped between storing a meal's answers and the profile version (kill -9) left the profile a
        // meal behind: the version is written now, from the same answers.
        if (profileVersions < static_cast<std::size_t>(r.meal)) {
          storeProfile(s, p, events, r.meal);
          ++profileVersions;
        }
      }
      if (!s.study->finished()) s.study->current();
    } catch (const std::exception& e) {
      s.study.reset();
      s.broken = fmt::format(
          "participant '{}' cannot be continued: {} (was the server started with other solver or text options than "
          "when they began?)",
          p.id, e.what());
    }
  }
  if (!s.broken.empty()) return errorReply(500, s.broken);
  return std::nullopt;
}

HttpReply StudyService::begin(const std::string& participant) {
  HttpReply reply = beginUnlogged(participant);
  logReply(participant, "begin", reply);
  return reply;
}

HttpReply StudyService::record(const std::string& participant, const std::string& body) {
  HttpReply reply = recordUnlogged(participant, body);
  // Which page, from the request: only the kind, meal and trial (never the answers) reach the log.
  const json request = json::parse(body, nullptr, false);
  std::string what = "record";
  if (request.is_object())
    what = fmt::format("trial {} ({}, meal {})", logText(request.value("trial_index", json())),
                       logText(request.value("kind", json())), logText(request.value("meal", json())));
  logReply(participant, what, reply);
  return reply;
}

void StudyService::logReply(const std::string& participant, const std::string& what, const HttpReply& reply) {
  if (!options_.log) return;
  // The id is printed as JSON text: a hostile one cannot forge log lines.
  const std::string id = logText(json(participant));
  const json r = json::parse(reply.body, nullptr, false);
  if (reply.status == 200) {
    const bool hasStatus = r.is_object() && r.contains("status") && r["status"].is_string();
    options_.log(fmt::format("participant {} {}: {}", id, what, hasStatus ? r["status"].get<std::string>() : "ok"));
    return;
  }
  // The reason up to its first ": ", where messages go on to quote what was sent or stored (answers stay out).
  std::string reason =
      r.is_object() && r.contains("error") && r["error"].is_string() ? r["error"].get<std::string>() : "";
  reason = reason.substr(0, reason.find(": "));
  options_.log(fmt::format("participant {} {}: refused {} {}", id, what, reply.status, logText(json(reason))));
}

HttpReply StudyService::beginUnlogged(const std::string& participant) {
  if (!isParticipantId(participant)) return errorReply(400, invalidIdMessage(participant));
  Participant p;
  try {
    std::lock_guard<std::mutex> lock(dbMutex_);
    const json options = {{"study_seed", options_.study.seed}, {"exploring_view", options_.study.askExploringView}};
    p = records_.begin(participant, records_.participants().size(), options.dump());
  } catch (const StudyError& e) {
    return storageError(e);
  }
  Lease held = lease(p);
  return stateReply(held.session(), p);
}

std::optional<HttpReply> StudyService::lookUp(const std::string& participant, Participant& out) {
  if (!isParticipantId(participant)) return errorReply(400, invalidIdMessage(participant));
  std::optional<Participant> p;
  {
    std::lock_guard<std::mutex> lock(dbMutex_);
    p = records_.participant(participant);
  }
  if (!p) return errorReply(404, fmt::format("no participant '{}': open their page to begin", participant));
  out = std::move(*p);
  return std::nullopt;
}

HttpReply StudyService::state(const std::string& participant) {
  Participant p;
  if (auto error = lookUp(participant, p)) return *error;
  Lease held = lease(p);
  return stateReply(held.session(), p);
}

HttpReply StudyService::stateReply(Session& s, const Participant& p, const char* status) {
  std::int64_t next = 0;
  {
    std::lock_guard<std::mutex> lock(dbMutex_);
    next = records_.nextTrial(p.id);
  }
  const StudyPage page = pageOfTrial(next);
  json state = {{"participant", p.id}, {"next_trial", next},   {"page", page.kind},      {"meal", page.meal},
                {"meals", kMeals},     {"pages", kStudyPages}, {"study", options_.about}};
  if (page.meal > 0) {
    // Only a meal's pages need the session: the pages before and after meals are answered without building one.
    if (auto error = ensureBuilt(s, p)) return *error;
    if (s.study->meal() + 1 != static_cast<std::size_t>(page.meal))
      return errorReply(500, fmt::format("participant '{}': the records are at meal {}, the session at meal {}", p.id,
                                         page.meal, s.study->meal() + 1));
    describeMeal(state, s.study->current(), page, p.id);
  }
  if (!status) return jsonReply(state);
  return jsonReply({{"status", status}, {"state", state}});
}

namespace {

// A record request's fields, checked for presence and type (not yet against the participant's pages).
struct RecordRequest {
  NewRecord record;
  json response;
};

std::optional<std::string> parseRecord(const std::string& participant, const std::string& body, RecordRequest& out) {
  const json j = json::parse(body, nullptr, false);
  if (j.is_discarded()) return std::string("the body is not JSON");
  if (!j.is_object()) return std::string("the body must be a JSON object");
  for (const char* key : {"trial_index", "kind", "meal", "elapsed_ms", "rt_ms", "response"})
    if (!j.contains(key)) return fmt::format("the record lacks the field '{}'", key);
  for (const char* key : {"trial_index", "meal", "elapsed_ms", "rt_ms"})
    if (!j[key].is_number_integer() || j[key].get<std::int64_t>() < 0)
      return fmt::format("{} must be a whole number >= 0", key);
  if (!j["kind"].is_string()) return std::string("kind must be text");
  if (j["meal"].get<std::int64_t>() > kMeals) return fmt::format("meal must be 0 to {}", kMeals);
  out.record = NewRecord{participant,     j["trial_index"], j["kind"], static_cast<int>(j["meal"].get<std::int64_t>()),
                         j["elapsed_ms"], j["rt_ms"],       ""};
  out.response = j["response"];
  return std::nullopt;
}

std::string pageName(const StudyPage& page) {
  return page.meal > 0 ? fmt::format("the '{}' page of meal {}", page.kind, page.meal)
                       : fmt::format("the '{}' page", page.kind);
}

}  // namespace

HttpReply StudyService::recordUnlogged(const std::string& participant, const std::string& body) {
  RecordRequest req;
  if (!isParticipantId(participant)) return errorReply(400, invalidIdMessage(participant));
  if (auto problem = parseRecord(participant, body, req)) return errorReply(400, *problem);
  Participant found;
  if (auto error = lookUp(participant, found)) return *error;
  const Participant* p = &found;
  Lease held = lease(*p);
  Session& s = held.session();
  const NewRecord& r = req.record;
  std::int64_t next = 0;
  std::optional<StoredRecord> earlier;
  {
    std::lock_guard<std::mutex> db(dbMutex_);
    next = records_.nextTrial(participant);
    if (r.trialIndex < next) earlier = records_.records(participant).at(static_cast<std::size_t>(r.trialIndex));
  }
  if (earlier) {
    const bool same = earlier->kind == r.kind && earlier->meal == r.meal &&
                      sentPart(r.kind, json::parse(earlier->response)) == req.response;
    if (!same)
      // Nothing stored is quoted: a reply is no way to read a participant's answers (their age, their comments).
      return errorReply(409, fmt::format("trial {} was already answered, differently: it is {}; an answer once "
                                         "stored is not changed",
                                         r.trialIndex, pageName(pageOfTrial(r.trialIndex))));
    return stateReply(s, *p, "replayed");
  }
  const StudyPage page = pageOfTrial(next);
  if (page.kind == "done") return errorReply(409, "this participant has finished the study");
  if (r.trialIndex > next)
    return errorReply(409, fmt::format("trial {} is not this participant's next page: that is trial {}, {}",
                                       r.trialIndex, next, pageName(page)));
  if (r.kind != page.kind || r.meal != page.meal)
    return errorReply(
        409, fmt::format("trial {} is {}, not kind {} of meal {}", next, pageName(page), quotedText(r.kind), r.meal));
  if (auto problem = checkResponse(r.kind, req.response)) return errorReply(400, *problem);
  if (page.meal > 0) {
    if (auto error = ensureBuilt(s, *p)) return *error;
  }
  NewRecord stored = r;
  stored.response = req.response.dump();
  if (r.kind == "answers") return storeAnswers(s, *p, stored);
  if (r.kind == "rating") stored.response = storedRating(req.response, s.study->current()).dump();
  try {
    std::lock_guard<std::mutex> db(dbMutex_);
    records_.record(stored);
    if (r.kind == "complete") records_.complete(participant);
  } catch (const StudyError& e) {
    return storageError(e);
  }
  HttpReply reply = stateReply(s, *p, "stored");
  if (r.kind == "complete") {
    std::lock_guard<std::mutex> lock(sessionsMutex_);
    s.finished = true;  // let go as the lease ends
  }
  return reply;
}

HttpReply StudyService::storeAnswers(Session& s, const Participant& p, const NewRecord& r) {
  const json response = json::parse(r.response);
  const feeding::ParticipantAnswers answers = participantAnswersOf(response);
  if (auto problem = s.study->check(answers)) return errorReply(400, *problem);
  const feeding::MealPresentation& m = s.study->current();
  NewRecord stored = r;
  stored.response = storedAnswers(response, m).dump();
  // Computed now: the session moves on below.
  const std::vector<profile::NewEvent> events = profileEvents(m, answers, lp_.graph());
  try {
    std::lock_guard<std::mutex> db(dbMutex_);
    records_.record(stored);
  } catch (const StudyError& e) {
    return storageError(e);
  }
  try {
    const auto plans = planning(s.planner->mutex);
    s.study->answer(answers);
    if (!s.study->finished()) s.study->current();
  } catch (const std::exception& e) {
    // The answers are stored; the session is rebuilt from the records on the next request, which says why it fails.
    s.study.reset();
    return errorReply(500,
                      fmt::format("participant '{}': meal {} could not be carried out: {}", p.id, r.meal, e.what()));
  }
  s.pictures.clear();
  storeProfile(s, p, events, r.meal);
  return stateReply(s, p, "stored");
}

// The profile is a copy of what the session learned, for `cbtl profile` and the REPL: a failure to write it is
// reported on the server's error stream and does not refuse the participant's answers, which are stored.
void StudyService::storeProfile(Session& s, const Participant& p, const std::vector<profile::NewEvent>& events,
                                int meal) {
  try {
    const model::UserModel& model = s.study->learnerModel();
    std::lock_guard<std::mutex> db(dbMutex_);
    profiles_.recordLearning(p.id, lp_.graph().domain, events, model.toJson(),
                             static_cast<std::int64_t>(model.dataCount()), fmt::format("study: meal {}", meal));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cbtl study serve: warning: the profile of '%s' was not updated: %s\n", p.id.c_str(),
                 e.what());
  }
}

HttpReply StudyService::view(const std::string& participant, int meal, int picture) {
  return withPicture(participant, meal, picture, [this](Session& s, std::size_t k) {
    if (!renderer_) return errorReply(503, noRendererReason_);
    return renderPicture(s, k);
  });
}

HttpReply StudyService::viewMeasure(const std::string& participant, int meal, int picture) {
  return withPicture(participant, meal, picture, [](Session& s, std::size_t k) {
    return jsonReply({{"occlusion", s.study->current().views.at(k).occlusion}});
  });
}

HttpReply StudyService::withPicture(const std::string& participant, int meal, int picture,
                                    const std::function<HttpReply(Session&, std::size_t)>& answer) {
  Participant found;
  if (auto error = lookUp(participant, found)) return *error;
  const Participant* p = &found;
  // Taken before the check: a participant's records are written only under their session's lease, so where they
  // are cannot change between the check and the picture.
  Lease held = lease(*p);
  std::int64_t next = 0;
  {
    std::lock_guard<std::mutex> db(dbMutex_);
    next = records_.nextTrial(participant);
  }
  const StudyPage page = pageOfTrial(next);
  if (page.meal != meal)
    return errorReply(404, fmt::format("no pictures of meal {} now: participant '{}' is at {}", meal, participant,
                                       page.kind == "done" ? "the end" : "trial " + std::to_string(next)));
  Session& s = held.session();
  if (auto error = ensureBuilt(s, *p)) return *error;
  const feeding::MealPresentation& m = s.study->current();
  if (picture < 0 || static_cast<std::size_t>(picture) >= m.views.size())
    return errorReply(404, fmt::format("meal {} has {} pictures (0 to {})", meal, m.views.size(),
                                       static_cast<int>(m.views.size()) - 1));
  return answer(s, static_cast<std::size_t>(picture));
}

HttpReply StudyService::renderPicture(Session& s, std::size_t picture) {
  const feeding::MealPresentation& m = s.study->current();
  if (s.picturesMeal != m.meal || s.pictures.size() != m.views.size()) {
    s.pictures.assign(m.views.size(), {});
    s.picturesMeal = m.meal;
  }
  std::vector<std::uint8_t>& png = s.pictures[picture];
  if (png.empty()) {
    std::lock_guard<std::mutex> lock(renderMutex_);
    if (pictureWorkspace_->setState(m.views[picture].state) != world::StateStatus::Ok)
      return errorReply(500, "the picture's scene could not be set up");
    world::CameraSpec camera;
    camera.name = "user_view";
    world::Image image;
    const world::RenderStatus status =
        renderer_->render(*pictureWorkspace_, camera, options_.pictureWidth, options_.pictureHeight, image);
    if (status != world::RenderStatus::Ok)
      return errorReply(500, fmt::format("the picture could not be rendered: {}", world::toString(status)));
    png = world::encodePng(image.width, image.height, image.rgb);
  }
  return HttpReply{200, "image/png", std::string(png.begin(), png.end())};
}

}  // namespace cbtl::app::study
