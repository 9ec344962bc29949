// A request fuzzer for the study server (StudyHttpServer behind ParticipantAccess and StudyService): 800
// seeded random requests, as raw bytes over TCP, mixing well-formed and broken request lines, methods, paths (known
// routes with mutated segments, invalid UTF-8, encoded control bytes, long ones), headers (keys right, wrong and
// malformed, Origins, content types, lengths that lie, chunked encodings) and bodies (mutated records, random bytes,
// deep or huge JSON). Every request must get an HTTP answer or a closed connection (what cpp-httplib does with a
// request it cannot parse), never a 5xx, and the server must answer a participant correctly afterwards. Run by `make
// asan` under AddressSanitizer and UBSan like every test. The seed is fixed: a failure reproduces.
#include "app/DomainSolverOptions.h"
#include "app/study/ParticipantAccess.h"
#include "app/study/StudyHttpServer.h"
#include "app/study/StudyService.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace cbtl::app::study {
namespace {

using nlohmann::json;

// Whether `reply` holds a whole response: its head and, unless it answers a HEAD, the Content-Length bytes after.
bool wholeResponse(const std::string& reply, bool head) {
  const std::size_t end = reply.find("\r\n\r\n");
  if (end == std::string::npos) return false;
  if (head) return true;
  std::size_t length = 0;
  const std::size_t at = reply.find("Content-Length: ");
  if (at != std::string::npos && at < end) length = std::strtoul(reply.c_str() + at + 16, nullptr, 10);
  return reply.size() >= end + 4 + length;
}

// Sends `request` as is and returns what the server answered: one whole response, or what came before it closed
// the connection (nothing, for a request it could not parse), or before 20 s passed. The connection stays open for
// writing: the server takes a half-closed one for a client that left, and does not answer it.
std::string sendRaw(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return "";
  timeval timeout{20, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string reply;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    std::size_t sent = 0;
    while (sent < request.size()) {
      const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    const bool head = request.compare(0, 5, "HEAD ") == 0;
    char buffer[8192];
    while (!wholeResponse(reply, head)) {
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      reply.append(buffer, static_cast<std::size_t>(n));
    }
  }
  ::close(fd);
  return reply;
}

// The status of the response in `reply`, as a list (empty: no answer).
std::vector<int> statusesOf(const std::string& reply) {
  if (reply.compare(0, 9, "HTTP/1.1 ") != 0 || reply.size() < 12) return {};
  return {std::atoi(reply.substr(9, 3).c_str())};
}

class RequestMaker {
 public:
  RequestMaker(std::uint32_t seed, std::string participant, std::string key)
      : random_(seed), participant_(std::move(participant)), key_(std::move(key)) {}

  std::string next() {
    const std::string method = pick({"GET", "POST", "POST", "POST", "PUT", "DELETE", "HEAD", "OPTIONS", "PATCH", "BREW",
                                     "G\x01T", "", std::string(300, 'P')});
    const std::string body = makeBody();
    std::string request = method + " " + makePath() + pick({" HTTP/1.1", " HTTP/1.0", " HTTP/9.9", "", " http/1.1"});
    request += "\r\nHost: " + pick({"127.0.0.1", "x", "", std::string(500, 'h')}) + "\r\n";
    for (int i = uniform(0, 5); i > 0; --i) request += makeHeader(body);
    if (chance(0.8)) request += "Content-Length: " + lengthOf(body) + "\r\n";
    if (chance(0.1)) request += "Transfer-Encoding: " + pick({"chunked", "gzip, chunked", "identity", "x"}) + "\r\n";
    request += chance(0.95) ? "\r\n" : "";
    return request + body;
  }

 private:
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(random_) < p; }
  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random_); }
  std::string pick(const std::vector<std::string>& options) {
    return options[static_cast<std::size_t>(uniform(0, static_cast<int>(options.size()) - 1))];
  }
  std::string bytes(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += static_cast<char>(uniform(0, 255));
    return s;
  }
  std::string percentBytes(int n) {
    static const char* hex = "0123456789abcdef";
    std::string s;
    for (int i = 0; i < n; ++i) {
      const int b = uniform(0, 255);
      s += '%';
      s += hex[b >> 4];
      s += hex[b & 15];
    }
    return s;
  }
  std::string segment() {
    switch (uniform(0, 7)) {
      case 0:
        return participant_;
      case 1:
        return "nobody";
      case 2:
        return percentBytes(uniform(1, 6));
      case 3:
        return std::string(static_cast<std::size_t>(uniform(60, 400)), 'a');
      case 4:
        return "..";
      case 5:
        return std::to_string(uniform(-5, 2000));
      case 6:
        return bytes(uniform(1, 4));
      default:
        return pick({"%00", "%2e%2e", "p1%2fviews", "%c3%28", "%ff"});
    }
  }
  std::string makePath() {
    const std::string id = segment();
    switch (uniform(0, 9)) {
      case 0:
        return "/";
      case 1:
        return "/?" + pick({"participant=", "PROLIFIC_PID=", "workerId="}) + segment();
      case 2:
        return "/p/" + id;
      case 3:
        return "/static/" + pick({"study.js", "study.css", "../study.js", "x"});
      case 4:
        return "/api/participants/" + id;
      case 5:
        return "/api/participants/" + id + "/records";
      case 6:
        return "/api/participants/" + id + "/views/" + segment() + "/" + segment() + ".png";
      case 7:
        return "/api/participants/" + id + "/views/1/0.json";
      case 8:
        return "/" + percentBytes(uniform(0, 20));
      default:
        return bytes(uniform(0, 30));
    }
  }
  std::string makeHeader(const std::string& body) {
    switch (uniform(0, 7)) {
      case 0:
        return "Authorization: Bearer " + (chance(0.5) ? key_ : bytes(uniform(0, 70))) + "\r\n";
      case 1:
        return "Authorization: " + pick({"Bearer", "Basic abc", "Bearer  " + key_, key_}) + "\r\n";
      case 2:
        return "Origin: " + pick({"http://127.0.0.1", "https://evil.example", "null", "", bytes(10)}) + "\r\n";
      case 3:
        return "Content-Type: " +
               pick({"application/json", "text/plain", "application/json; charset=x", "multipart/form-data; boundary=x",
                     ""}) +
               "\r\n";
      case 4:
        return "Content-Length: " + lengthOf(body) + "\r\n";  // a second one
      case 5:
        return "Sec-Fetch-Site: " + pick({"same-origin", "cross-site", "none"}) + "\r\n";
      case 6:
        return bytes(uniform(1, 40)) + ": " + bytes(uniform(0, 40)) + "\r\n";
      default:
        return "X-" + std::string(static_cast<std::size_t>(uniform(1, 9000)), 'y') + ": 1\r\n";
    }
  }
  std::string lengthOf(const std::string& body) {
    switch (uniform(0, 5)) {
      case 0:
        return std::to_string(body.size() + static_cast<std::size_t>(uniform(1, 100)));
      case 1:
        return std::to_string(body.size() / 2);
      case 2:
        return pick({"-1", "x", "99999999999999999999", "1e3", ""});
      default:
        return std::to_string(body.size());
    }
  }
  std::string makeBody() {
    json record = {{"trial_index", uniform(-2, 14)},
                   {"kind", pick({"consent", "demographics", "rating", "answers", "complete", "x"})},
                   {"meal", uniform(-1, 6)},
                   {"elapsed_ms", uniform(-10, 100000)},
                   {"rt_ms", uniform(-10, 100000)},
                   {"response", json::object()}};
    switch (uniform(0, 9)) {
      case 0:
        return "";
      case 1:
        return bytes(uniform(1, 300));
      case 2:
        return std::string(static_cast<std::size_t>(uniform(1, 3000)), '[');
      case 3:
        return std::string(70000, ' ');
      case 4:
        record["response"] = {{"agree", chance(0.5)}};
        break;
      case 5:
        record["response"] = {{"likert", uniform(-1, 7)}};
        break;
      case 6:
        record["response"] = {{"age", uniform(0, 200)}, {"gender", "other"}, {"gender_other", bytes(20)}};
        break;
      case 7:
        record["response"] = {{"dip", bytes(5)}, {"blocked", json::array({true, 1, nullptr})}};
        break;
      case 8:
        record.erase(pick({"trial_index", "kind", "meal", "elapsed_ms", "rt_ms", "response"}));
        break;
      default:
        return "{}";
    }
    return record.dump(-1, ' ', false, json::error_handler_t::replace);
  }

  std::mt19937 random_;
  std::string participant_, key_;
};

TEST(StudyHttpFuzz, RandomRequestsAreAnsweredAndNeverStopTheServer) {
  static const auto lp = LoadedProgram::load(std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.cbtl");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const auto dir = std::filesystem::temp_directory_path() / ("cbtl-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "study.sqlite").string();
  {
    StudyServiceOptions options;
    options.study.solver = domainSolverOptions("feeding");
    options.pictures = false;
    StudyService service(*lp, test::programFacts("feeding"), options, db);
    ParticipantAccess access(service, db, AdmissionOptions{0, 0, 0});
    HttpServerLimits limits;
    limits.readTimeoutSeconds = 1;  // a request that lies about its length is given up on quickly
    StudyHttpServer server(access, limits);
    std::string error;
    const int port = server.bind("127.0.0.1", 0, error);
    ASSERT_GT(port, 0) << error;
    std::thread listening([&] { server.listen(); });
    const HttpReply begun = access.begin("fz", "");
    ASSERT_EQ(begun.status, 200) << begun.body;
    const std::string key = json::parse(begun.body)["key"];

    RequestMaker maker(20261208, "fz", key);
    std::map<int, int> statuses;
    int closedWithoutAnswer = 0;
    for (int i = 0; i < 800; ++i) {
      const std::string request = maker.next();
      const std::vector<int> answered = statusesOf(sendRaw(port, request));
      if (answered.empty()) ++closedWithoutAnswer;
      if (std::getenv("CBTL_FUZZ_TRACE") != nullptr && answered.empty())
        std::printf("request %d: no answer: %s\n", i,
                    json(request.substr(0, 200)).dump(-1, ' ', true, json::error_handler_t::replace).c_str());
      for (const int status : answered) {
        ++statuses[status];
        EXPECT_LT(status, 500) << "request " << i << " was answered " << status << ": "
                               << json(request.substr(0, 300)).dump(-1, ' ', true, json::error_handler_t::replace);
      }
    }
    std::string summary;
    for (const auto& [status, count] : statuses) summary += " " + std::to_string(status) + "x" + std::to_string(count);
    std::printf("statuses:%s; closed without an answer: %d\n", summary.c_str(), closedWithoutAnswer);
    // The participant is served as before: their state, with their key.
    const std::string after = sendRaw(port, "GET /api/participants/fz HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
                                                key + "\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statusesOf(after), std::vector<int>{200}) << after.substr(0, 300);
    server.stop();
    listening.join();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cbtl::app::study
