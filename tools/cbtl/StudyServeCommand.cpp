// `cbtl study serve`: the web study (app/study/StudyService.h behind app/study/StudyHttpServer.h) until SIGINT or
// SIGTERM. The first line on stdout is "listening on http://<host>:<port>/", so that scripts and tests can start
// the server on port 0 and read the port it got.
#include "tools/cbtl/StudyCommands.h"

#include "app/SimulatorFacts.h"
#include "app/study/ParticipantAccess.h"
#include "app/study/StudyHttpServer.h"
#include "app/study/StudyInfo.h"
#include "app/study/StudyService.h"

#include <fmt/core.h>

#include <pthread.h>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <thread>

namespace cbtl::cli {

namespace {

// Stops the server on SIGINT or SIGTERM: the signals are blocked in every thread (the server's pool inherits the
// mask of the thread that starts it) and one thread waits for them, so no handler runs in an arbitrary thread.
class StopOnSignal {
 public:
  explicit StopOnSignal(app::study::StudyHttpServer& server) : server_(server) {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    sigaddset(&signals_, SIGUSR2);  // our own wake-up when the server stopped by itself
    pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
    waiter_ = std::thread([this] {
      int received = 0;
      sigwait(&signals_, &received);
      if (received != SIGUSR2) server_.stop();
    });
  }
  ~StopOnSignal() {
    pthread_kill(waiter_.native_handle(), SIGUSR2);
    waiter_.join();
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

 private:
  app::study::StudyHttpServer& server_;
  sigset_t signals_{};
  std::thread waiter_;
};

}  // namespace

int runStudyServe(const StudyArgs& a) {
  app::study::StudyServiceOptions options;
  auto lp = loadFeedingStudy("study serve", a, options.study);
  if (!lp) return 1;
  options.pictures = !a.noPictures;
  options.pictureWidth = a.width;
  options.pictureHeight = a.height;
  options.maxSessions = static_cast<std::size_t>(a.maxSessions);
  if (!a.studyInfo.empty()) {
    try {
      options.about = app::study::readStudyInfo(a.studyInfo);
    } catch (const app::study::StudyInfoError& e) {
      fmt::print(stderr, "cbtl study serve: error: {}\n", e.what());
      return 1;
    }
  }
  // One line per participant event on stderr, with the time (UTC), for whoever runs the study.
  options.log = [](const std::string& line) {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &utc);
    fmt::print(stderr, "{} {}\n", stamp, line);
  };
  const domains::ProgramFacts facts = app::simulatorFacts(*lp);
  // One planner per core: the program is loaded again for each (a session plans with one copy, not thread-safe).
  const int planners =
      a.planners > 0 ? a.planners : std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8);
  std::vector<std::unique_ptr<app::LoadedProgram>> copies;
  std::vector<const approach::PreparedProgram*> morePlanners;
  for (int k = 1; k < planners; ++k) {
    domains::feeding::StudyOptions same;
    copies.push_back(loadFeedingStudy("study serve", a, same));
    if (!copies.back()) return 1;
    morePlanners.push_back(copies.back().get());
  }
  app::study::StudyService service(*lp, facts, options, a.db, morePlanners);
  if (!service.pictureProblem().empty() && !a.noPictures)
    fmt::print(stderr, "cbtl study serve: warning: {}; the view pictures will be answered 503\n",
               service.pictureProblem());
  app::study::AdmissionOptions admission;
  admission.perMinute = a.newParticipantsPerMinute;
  admission.total = a.maxParticipants;
  app::study::ParticipantAccess access(service, a.db, admission);
  app::study::HttpServerLimits limits;
  limits.connections = a.connections;
  app::study::StudyHttpServer server(access, limits);
  std::string error;
  const int port = server.bind(a.host, a.port, error);
  if (port < 0) {
    fmt::print(stderr, "cbtl study serve: error: {}\n", error);
    return 1;
  }
  if (a.host != "127.0.0.1" && a.host != "localhost" && a.host != "::1")
    fmt::print(stderr,
               "cbtl study serve: warning: listening on {}: other machines can reach the study without encryption; "
               "put it behind a TLS reverse proxy (docs/study.md, Deploying)\n",
               a.host);
  fmt::print("listening on http://{}:{}/\n", a.host, port);
  fmt::print("participants' pages: http://{}:{}/p/<participant id>; database {}; Ctrl-C stops\n", a.host, port, a.db);
  std::fflush(stdout);
  StopOnSignal stopper(server);
  if (!server.listen()) {
    fmt::print(stderr, "cbtl study serve: error: stopped listening on {}:{}\n", a.host, port);
    return 1;
  }
  fmt::print("stopped\n");
  return 0;
}

}  // namespace cbtl::cli
