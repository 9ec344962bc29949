// StudyHttpServer.h — the web study's HTTP side (`cbtl study serve`): the pages embedded at build time
// (app/study/web, studyWebFiles()) and the JSON API of docs/study-api.md, routed through ParticipantAccess (the
// participant's key) to the study. The routes, their methods, the id syntax and what a request must look like are
// checked here; everything a route means is the study's.
//
// Routes: GET /p/<id> (the study page), GET /static/<file> (its script and style), POST and GET
// /api/participants/<id>, POST /api/participants/<id>/records, GET /api/participants/<id>/views/<meal>/<k>.png,
// GET /api/participants/<id>/views/<meal>/<k>.json, GET / (how to reach one's page). Anything else is 404 with a
// JSON error. The key travels as "Authorization: Bearer <key>".
//
// What a request must be (each refusal a JSON error, nothing changed):
// - bodies at most 64 KiB (413), sent with a Content-Length (411: chunked uploads are not read);
// - a POST with a body is `Content-Type: application/json` (415), and a POST a browser sends from another site
//   (an Origin other than the Host it was sent to, or Sec-Fetch-Site cross-site) is 403: a page elsewhere cannot
//   answer in a participant's name, and with JSON only, no cross-site form can either.
// An exception escaping the study is answered 500 with its message.
//
// Connections: `connections` threads answer requests; each waits at most `readTimeoutSeconds` for the next bytes
// of a request and keeps an idle connection `keepAliveSeconds`. A client that sends slowly holds one thread, so
// slow clients take the study down only when they hold all of them: put the server behind a reverse proxy that
// buffers requests before exposing it (docs/study.md, "Deploying").
//
// Threads: requests run concurrently, so the study (StudyApi) must be safe to call concurrently.
#pragma once

#include "app/study/StudyApi.h"

#include <map>
#include <memory>
#include <string>
#include <string_view>

namespace httplib {
class Server;
}

namespace cbtl::app::study {

// The pages, by file name ("study.html", "study.js", "study.css"), as they were when the binary was built.
const std::map<std::string, std::string_view>& studyWebFiles();

class ParticipantAccess;

struct HttpServerLimits {
  int connections = 128;       // requests answered at once (threads); more wait for one to be free
  int readTimeoutSeconds = 5;  // the longest wait for a request's next bytes
  int keepAliveSeconds = 5;    // an idle kept-alive connection is closed after this
};

class StudyHttpServer {
 public:
  explicit StudyHttpServer(ParticipantAccess& access, HttpServerLimits limits = {});
  ~StudyHttpServer();
  StudyHttpServer(const StudyHttpServer&) = delete;
  StudyHttpServer& operator=(const StudyHttpServer&) = delete;

  // Binds host:port (port 0: any free port). Returns the port bound, or -1 (the reason in `error`).
  int bind(const std::string& host, int port, std::string& error);
  // Answers requests until stop(); returns false if it could not listen.
  bool listen();
  // Makes listen() return; safe from any thread, including a signal-watching one.
  void stop();

 private:
  void routes();
  ParticipantAccess& access_;
  std::unique_ptr<httplib::Server> server_;
};

}  // namespace cbtl::app::study
