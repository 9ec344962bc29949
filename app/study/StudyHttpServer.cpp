#include "app/study/StudyHttpServer.h"

#include "app/study/StudyRecords.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <exception>

namespace cbtl::app::study {

namespace {

constexpr std::size_t kMaxBody = 64 * 1024;

// The API's answers must never be cached: a participant's state changes with every answer.
void send(httplib::Response& res, const HttpReply& reply) {
  res.status = reply.status;
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_content(reply.body, reply.contentType.c_str());
}

std::string contentTypeOf(const std::string& file) {
  auto endsWith = [&](const char* suffix) {
    const std::string s(suffix);
    return file.size() >= s.size() && file.compare(file.size() - s.size(), s.size(), s) == 0;
  };
  if (endsWith(".html")) return "text/html; charset=utf-8";
  if (endsWith(".js")) return "text/javascript; charset=utf-8";
  if (endsWith(".css")) return "text/css; charset=utf-8";
  if (endsWith(".png")) return "image/png";
  return "application/octet-stream";
}

HttpReply fileReply(const std::string& name) {
  const auto& files = studyWebFiles();
  auto it = files.find(name);
  if (it == files.end()) return errorReply(404, "no such file: " + name);
  return HttpReply{200, contentTypeOf(name), std::string(it->second)};
}

const char* kIndexPage =
    "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" "
    "content=\"width=device-width, initial-scale=1\"><title>CBTL study</title></head><body><main><h1>CBTL feeding "
    "study</h1><p>Open the link you were given: it ends in <code>/p/</code> and your participant id.</p></main>"
    "</body></html>";

}  // namespace

HttpReply errorReply(int status, const std::string& message) {
  // A message may quote what a client sent (a path, an id): bytes that are not UTF-8 become U+FFFD instead of
  // throwing out of the server's thread (`GET /%ff` once aborted the process).
  return HttpReply{status, "application/json",
                   nlohmann::json{{"error", message}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)};
}

StudyHttpServer::StudyHttpServer(StudyApi& api) : api_(api), server_(std::make_unique<httplib::Server>()) {
  server_->set_payload_max_length(kMaxBody);
  // cpp-httplib's default also sets SO_REUSEPORT, with which a second server binds a port in use and the kernel
  // shares the connections between the two (two studies, two databases, one URL). SO_REUSEADDR alone lets a
  // restarted server take its port back at once and refuses a port another server is listening on.
  server_->set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const void*>(&yes), sizeof(yes));
  });
  routes();
}

StudyHttpServer::~StudyHttpServer() = default;

void StudyHttpServer::routes() {
  httplib::Server& s = *server_;
  // The id pattern is wider than a valid id on purpose: an invalid one gets the records' explanation, not a 404.
  const std::string id = R"(/api/participants/([^/]{1,200}))";
  // Recruiting sites pass the id as a query parameter: /?participant=<id> (or PROLIFIC_PID, workerId) goes to the
  // participant's page.
  s.Get("/", [](const httplib::Request& req, httplib::Response& res) {
    for (const char* key : {"participant", "PROLIFIC_PID", "workerId"}) {
      if (!req.has_param(key)) continue;
      const std::string given = req.get_param_value(key);
      if (!isParticipantId(given)) {
        send(res, errorReply(400, "the participant id " + quotedText(given) +
                                      " is not 1 to 64 characters of A-Z, a-z, 0-9, '_', '.', '-'"));
        return;
      }
      res.set_redirect("/p/" + given, 302);
      return;
    }
    send(res, HttpReply{200, "text/html; charset=utf-8", kIndexPage});
  });
  s.Get(R"(/p/([^/]{1,200}))", [](const httplib::Request& req, httplib::Response& res) {
    if (!isParticipantId(req.matches[1])) {
      send(res, HttpReply{404, "text/html; charset=utf-8", kIndexPage});
      return;
    }
    send(res, fileReply("study.html"));
    res.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'");
  });
  s.Get(R"(/static/(study\.(?:js|css)))",
        [](const httplib::Request& req, httplib::Response& res) { send(res, fileReply(req.matches[1])); });
  s.Post(id, [this](const httplib::Request& req, httplib::Response& res) { send(res, api_.begin(req.matches[1])); });
  s.Get(id, [this](const httplib::Request& req, httplib::Response& res) { send(res, api_.state(req.matches[1])); });
  s.Post(id + "/records", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, api_.record(req.matches[1], req.body));
  });
  s.Get(id + R"(/views/(\d{1,3})/(\d{1,3})\.png)", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, api_.view(req.matches[1], std::stoi(req.matches[2]), std::stoi(req.matches[3])));
  });
  s.Get(id + R"(/views/(\d{1,3})/(\d{1,3})\.json)", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, api_.viewMeasure(req.matches[1], std::stoi(req.matches[2]), std::stoi(req.matches[3])));
  });
  // cpp-httplib's payload limit holds only for bodies with a Content-Length: a chunked upload was read whole (a
  // 400 MB one took the server from 377 MB to 1.76 GB). The study's page always sends a Content-Length, so a request
  // with a Transfer-Encoding, or a POST without a Content-Length, is refused before any of its body is read, and
  // its connection closed (the unread body must not be taken for the next request).
  s.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!req.has_header("Transfer-Encoding") && (req.method != "POST" || req.has_header("Content-Length")))
      return httplib::Server::HandlerResponse::Unhandled;
    send(res, errorReply(411, "send the body with a Content-Length (at most 64 KiB); chunked uploads are refused"));
    res.set_header("Connection", "close");
    return httplib::Server::HandlerResponse::Handled;
  });
  s.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;  // a route's own error reply
    std::string message = "no such page: " + quotedText(req.method) + " " + quotedText(req.path);
    if (res.status == 413) message = "the request is too large (at most 64 KiB)";
    send(res, errorReply(res.status, message));
  });
  s.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string message = "internal error";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      message = std::string("internal error: ") + e.what();
    } catch (...) {}
    send(res, errorReply(500, message));
  });
}

int StudyHttpServer::bind(const std::string& host, int port, std::string& error) {
  const int bound = port == 0 ? server_->bind_to_any_port(host) : (server_->bind_to_port(host, port) ? port : -1);
  if (bound < 0) error = "cannot listen on " + host + ":" + std::to_string(port) + " (in use, or not an address here)";
  return bound;
}

bool StudyHttpServer::listen() { return server_->listen_after_bind(); }

void StudyHttpServer::stop() { server_->stop(); }

}  // namespace cbtl::app::study
