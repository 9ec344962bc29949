// StudyApi.h — what the web study answers, as the HTTP server routes it (StudyHttpServer.h): a reply type and the
// study's operations on a participant, each named by the id in the request's path. Implemented by StudyService;
// ParticipantAccess checks the participant's key before calling it.
#pragma once

#include <string>

namespace cbtl::app::study {

struct HttpReply {
  int status = 200;
  std::string contentType = "application/json";
  std::string body;
  int retryAfterSeconds = 0;  // > 0: sent as a Retry-After header (with 429 and 503)
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

}  // namespace cbtl::app::study
