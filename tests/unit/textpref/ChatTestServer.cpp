#include "tests/unit/textpref/ChatTestServer.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace cbtl::textpref::testing {

ChatTestServer::ChatTestServer() {
  default_ = reply(500, errorBody("no scripted response left", "server_error", "test_script_empty"));
  server_.Post(R"(/v1/chat/completions)", [this](const httplib::Request& req, httplib::Response& res) {
    Handler handler;
    {
      std::lock_guard lock(mutex_);
      RecordedRequest r;
      r.path = req.path;
      r.body = nlohmann::json::parse(req.body, nullptr, false);
      r.authorization = req.get_header_value("Authorization");
      requests_.push_back(std::move(r));
      if (!script_.empty()) {
        handler = std::move(script_.front());
        script_.pop_front();
      } else {
        handler = default_;
      }
    }
    handler(req, res);
  });
  port_ = server_.bind_to_any_port("127.0.0.1");
  if (port_ <= 0) throw std::runtime_error("cannot bind a loopback port");
  thread_ = std::thread([this] { server_.listen_after_bind(); });
  // The socket already listens after bind_to_any_port; wait (bounded) until the accept loop runs too.
  for (int i = 0; i < 2000 && !server_.is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

ChatTestServer::~ChatTestServer() {
  stopping_ = true;
  server_.stop();
  if (thread_.joinable()) thread_.join();
}

ChatTestServer::Handler ChatTestServer::hang() const {
  return [this](const httplib::Request&, httplib::Response& res) {
    for (int i = 0; i < 2000 && !stopping(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    res.status = 500;  // only sent if the client is still waiting after the bounded wait
    res.set_content(errorBody("the test server hung", "server_error", "test_hang"), "application/json");
  };
}

std::string ChatTestServer::baseUrl() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }

void ChatTestServer::push(Handler handler) {
  std::lock_guard lock(mutex_);
  script_.push_back(std::move(handler));
}

void ChatTestServer::setDefault(Handler handler) {
  std::lock_guard lock(mutex_);
  default_ = std::move(handler);
}

std::vector<RecordedRequest> ChatTestServer::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}

int ChatTestServer::requestCount() const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(requests_.size());
}

std::string ratingBody(const std::vector<std::pair<std::string, double>>& top) {
  nlohmann::json alternatives = nlohmann::json::array();
  for (const auto& [token, p] : top)
    alternatives.push_back({{"token", token}, {"logprob", std::log(p)}, {"bytes", nullptr}});
  const std::string content = top.empty() ? "" : top.front().first;
  nlohmann::json body{{"id", "chatcmpl-test"},
                      {"object", "chat.completion"},
                      {"model", "test-model"},
                      {"system_fingerprint", "fp_test"},
                      {"choices",
                       {{{"index", 0},
                         {"finish_reason", "length"},
                         {"message", {{"role", "assistant"}, {"content", content}}},
                         {"logprobs",
                          {{"content",
                            {{{"token", content},
                              {"logprob", top.empty() ? 0.0 : std::log(top.front().second)},
                              {"top_logprobs", alternatives}}}}}}}}}};
  return body.dump();
}

std::string textBody(const std::string& content) {
  nlohmann::json body{{"id", "chatcmpl-test"},
                      {"object", "chat.completion"},
                      {"choices",
                       {{{"index", 0},
                         {"finish_reason", "stop"},
                         {"message", {{"role", "assistant"}, {"content", content}}},
                         {"logprobs", nullptr}}}}};
  return body.dump();
}

std::string errorBody(const std::string& message, const std::string& type, const std::string& code) {
  return nlohmann::json{{"error", {{"message", message}, {"type", type}, {"param", nullptr}, {"code", code}}}}.dump();
}

ChatTestServer::Handler reply(int status, std::string body, std::vector<std::pair<std::string, std::string>> headers) {
  return
      [status, body = std::move(body), headers = std::move(headers)](const httplib::Request&, httplib::Response& res) {
        res.status = status;
        for (const auto& [k, v] : headers) res.set_header(k, v);
        res.set_content(body, "application/json");
      };
}

ChatTestServer::Handler replyRating(const std::vector<std::pair<std::string, double>>& top) {
  return reply(200, ratingBody(top));
}

}  // namespace cbtl::textpref::testing

namespace cbtl::textpref::testing {

ChatTestServer::Handler echoAuthorization(int status) {
  return [status](const httplib::Request& req, httplib::Response& res) {
    res.status = status;
    const std::string message = "Incorrect API key provided: " + req.get_header_value("Authorization") +
                                ". You can find your API key at https://example.invalid/keys.";
    res.set_content(errorBody(message, "invalid_request_error", "invalid_api_key"), "application/json");
  };
}

int unusedLoopbackPort() {
  ChatTestServer gone;  // listens, then stops and closes its socket
  return gone.port();
}

}  // namespace cbtl::textpref::testing
