// StudyHttpServer.h — the web study's HTTP side (`cbtl study serve`): the pages embedded at build time
// (app/study/web, studyWebFiles()) and the JSON API of docs/study-api.md, routed to a StudyApi that knows the
// study's content. The routes, their methods and the id syntax are checked here; everything a route means is the
// StudyApi's.
//
// Routes: GET /p/<id> (the study page), GET /static/<file> (its script and style), POST and GET
// /api/participants/<id>, POST /api/participants/<id>/records, GET /api/participants/<id>/views/<meal>/<k>.png,
// GET /api/participants/<id>/views/<meal>/<k>.json, GET / (how to reach one's page). Anything else is 404 with a
// JSON error.
// Bodies above 64 KiB are refused (413). An exception escaping the StudyApi is answered 500 with its message.
//
// Threads: cpp-httplib answers requests on a pool of threads, so a StudyApi must be safe to call concurrently.
#pragma once

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

struct HttpReply {
  int status = 200;
  std::string contentType = "application/json";
  std::string body;
};

// {"error": message} with `status`.
HttpReply errorReply(int status, const std::string& message);

class StudyApi {
 public:
  virtual ~StudyApi() = default;
  virtual HttpReply begin(const std::string& participant) = 0;
  virtual HttpReply state(const std::string& participant) = 0;
  virtual HttpReply record(const std::string& participant, const std::string& body) = 0;
  virtual HttpReply view(const std::string& participant, int meal, int picture) = 0;
  // What a simulated participant judges a picture by (its occlusion score); the pages never ask for it.
  virtual HttpReply viewMeasure(const std::string& participant, int meal, int picture) = 0;
};

class StudyHttpServer {
 public:
  explicit StudyHttpServer(StudyApi& api);
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
  StudyApi& api_;
  std::unique_ptr<httplib::Server> server_;
};

}  // namespace cbtl::app::study
