// ChatTestServer.h — an in-process chat-completions server on 127.0.0.1 (ephemeral port) for protocol tests.
//
// Each request is answered by the next scripted handler, or by the default handler when the script is empty.
// Every request is recorded (body and Authorization header). The server never binds anything but 127.0.0.1.
// Fault injection: hang() accepts a request and never answers it (until the client gives up, the server stops,
// or a bounded 10 s pass); echoAuthorization() quotes the Authorization header back in an error body, as servers
// that print "Incorrect API key provided: ..." do; reply(200, "garbage") gives a malformed reply; a port
// nothing listens on (unusedLoopbackPort()) gives a transport failure.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace cbtl::textpref::testing {

struct RecordedRequest {
  std::string path;
  nlohmann::json body;
  std::string authorization;
};

class ChatTestServer {
 public:
  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;

  ChatTestServer();
  ~ChatTestServer();
  ChatTestServer(const ChatTestServer&) = delete;
  ChatTestServer& operator=(const ChatTestServer&) = delete;

  int port() const { return port_; }
  std::string baseUrl() const;  // http://127.0.0.1:<port>/v1

  void push(Handler handler);
  void setDefault(Handler handler);
  std::vector<RecordedRequest> requests() const;
  int requestCount() const;
  // True once the destructor started; slow handlers poll it so that shutdown is quick.
  bool stopping() const { return stopping_; }
  // A handler that never answers: it waits (polling stopping(), at most 10 s) and then closes without a reply.
  Handler hang() const;

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = -1;
  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  std::deque<Handler> script_;
  Handler default_;
  std::vector<RecordedRequest> requests_;
};

// A chat-completions body whose first token has the given top alternatives (token, probability). The first
// alternative is the generated content.
std::string ratingBody(const std::vector<std::pair<std::string, double>>& top);
// A chat-completions body with text content and no logprobs.
std::string textBody(const std::string& content);
// An OpenAI error body.
std::string errorBody(const std::string& message, const std::string& type, const std::string& code);

// Handlers.
ChatTestServer::Handler reply(int status, std::string body,
                              std::vector<std::pair<std::string, std::string>> headers = {});
ChatTestServer::Handler replyRating(const std::vector<std::pair<std::string, double>>& top);
// `status` with an OpenAI error body "Incorrect API key provided: <the request's Authorization header>".
ChatTestServer::Handler echoAuthorization(int status);

// A loopback port on which nothing listens (bound once, then released).
int unusedLoopbackPort();

}  // namespace cbtl::textpref::testing
