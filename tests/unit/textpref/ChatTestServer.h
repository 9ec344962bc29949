// ChatTestServer.h — an in-process chat-completions server on 127.0.0.1 (ephemeral port) for protocol tests.
//
// Each request is answered by the next scripted handler, or by the default handler when the script is empty.
// Every request is recorded (body and Authorization header). The server never binds anything but 127.0.0.1.
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

}  // namespace cbtl::textpref::testing
