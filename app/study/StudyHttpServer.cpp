#include "app/study/StudyHttpServer.h"

#include "app/study/ParticipantAccess.h"
#include "app/study/StudyRecords.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <exception>
#include <string>
#include <utility>

namespace cbtl::app::study {

namespace {

constexpr std::size_t kMaxBody = 64 * 1024;

// The API's answers must never be cached: a participant's state changes with every answer.
void send(httplib::Response& res, const HttpReply& reply) {
  res.status = reply.status;
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  if (reply.retryAfterSeconds > 0) res.set_header("Retry-After", std::to_string(reply.retryAfterSeconds));
  res.set_content(reply.body, reply.contentType.c_str());
}

// The participant's key from "Authorization: Bearer <key>" ("" without one).
std::string keyOf(const httplib::Request& req) {
  const std::string auth = req.get_header_value("Authorization");
  const std::string scheme = "Bearer ";
  return auth.compare(0, scheme.size(), scheme) == 0 ? auth.substr(scheme.size()) : std::string();
}

// The host:port part of an Origin ("https://study.example.org:8443" -> "study.example.org:8443").
std::string originHost(const std::string& origin) {
  const auto scheme = origin.find("://");
  return scheme == std::string::npos ? origin : origin.substr(scheme + 3);
}

// Why a POST cannot be taken, or {0, ""} when it can: from another site (by its Origin or Sec-Fetch-Site), or a
// body that is not declared JSON. Called before the body is read, so the body is known by its Content-Length.
std::pair<int, std::string> postRefusal(const httplib::Request& req) {
  if (req.get_header_value("Sec-Fetch-Site") == "cross-site")
    return {403, "requests from other sites are refused: open the study's own page"};
  if (req.has_header("Origin") && originHost(req.get_header_value("Origin")) != req.get_header_value("Host"))
    return {403, "requests from other sites are refused: open the study's own page"};
  if (req.get_header_value("Content-Length") != "0") {
    const std::string type = req.get_header_value("Content-Type");
    if (type.compare(0, 16, "application/json") != 0)
      return {415, "send the body as JSON (Content-Type: application/json)"};
  }
  return {0, ""};
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

StudyHttpServer::StudyHttpServer(ParticipantAccess& access, HttpServerLimits limits)
    : access_(access), server_(std::make_unique<httplib::Server>()) {
  server_->set_payload_max_length(kMaxBody);
  const auto threads = static_cast<std::size_t>(std::max(1, limits.connections));
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_read_timeout(limits.readTimeoutSeconds, 0);
  server_->set_write_timeout(limits.readTimeoutSeconds, 0);
  server_->set_keep_alive_timeout(limits.keepAliveSeconds);
  // cpp-httplib's default also sets SO_REUSEPORT, with which a second server binds a port in use and the kernel
  // shares the connections between the two (two studies, two databases, one URL). SO_REUSEADDR alone lets a
  // restarted server take its port back at once and refuses a port another server is listening on.
  // TCP_NODELAY, which Linux gives every accepted connection from the listening socket: the reply's head and body
  // are two writes, and without it the second waited for the client's delayed acknowledgement (40 ms a request).
  server_->set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const void*>(&yes), sizeof(yes));
    setsockopt(sock, IPPROTO_TCP, TCP_NODELAY, reinterpret_cast<const void*>(&yes), sizeof(yes));
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
    res.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' data: blob:; frame-ancestors 'none'");
  });
  s.Get(R"(/static/(study\.(?:js|css)))",
        [](const httplib::Request& req, httplib::Response& res) { send(res, fileReply(req.matches[1])); });
  s.Post(id, [this](const httplib::Request& req, httplib::Response& res) {
    send(res, access_.begin(req.matches[1], keyOf(req)));
  });
  s.Get(id, [this](const httplib::Request& req, httplib::Response& res) {
    send(res, access_.state(req.matches[1], keyOf(req)));
  });
  s.Post(id + "/records", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, access_.record(req.matches[1], keyOf(req), req.body));
  });
  s.Get(id + R"(/views/(\d{1,3})/(\d{1,3})\.png)", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, access_.view(req.matches[1], keyOf(req), std::stoi(req.matches[2]), std::stoi(req.matches[3])));
  });
  s.Get(id + R"(/views/(\d{1,3})/(\d{1,3})\.json)", [this](const httplib::Request& req, httplib::Response& res) {
    send(res, access_.viewMeasure(req.matches[1], keyOf(req), std::stoi(req.matches[2]), std::stoi(req.matches[3])));
  });
  // cpp-httplib's payload limit holds only for bodies with a Content-Length: a chunked upload was read whole (a
  // 400 MB one took the server from 377 MB to 1.76 GB). The study's page always sends a Content-Length, so a request
  // with a Transfer-Encoding, or a POST without a Content-Length, is refused before any of its body is read, and
  // its connection closed (the unread body must not be taken for the next request).
  s.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (req.has_header("Transfer-Encoding") || (req.method == "POST" && !req.has_header("Content-Length"))) {
      send(res, errorReply(411, "send the body with a Content-Length (at most 64 KiB); chunked uploads are refused"));
      res.set_header("Connection", "close");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (req.method == "POST") {
      const auto [status, why] = postRefusal(req);
      if (status != 0) {
        send(res, errorReply(status, why));
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    return httplib::Server::HandlerResponse::Unhandled;
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
