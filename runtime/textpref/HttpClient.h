// HttpClient.h — one HTTP POST over libcurl, no retries (RetryPolicy.h and ChatClient.h add those).
//
// Proxies are never used (CURLOPT_NOPROXY "*"), so loopback tests cannot be rerouted by *_proxy variables.
// Request headers may hold secrets (Authorization): this class never logs or stores them. Transport failures
// become Error values (Transport or Timeout) naming the server; any HTTP status, 2xx or not, is a successful
// HttpResponse for the caller to judge.
#pragma once

#include "runtime/textpref/Result.h"

#include <map>
#include <string>
#include <vector>

namespace cbtl::textpref {

struct HttpRequest {
  std::string url;                          // absolute http:// or https:// URL
  std::string body;                         // sent as application/json
  std::vector<std::string> headers;         // extra "Name: value" lines; may contain secrets, never logged
  long connectTimeoutMs = 5000;             // time allowed to establish the connection
  long totalTimeoutMs = 60000;              // time allowed for the whole request, connection included
  std::size_t maxResponseBytes = 8u << 20;  // a larger body aborts the transfer with a Transport error
};

struct HttpResponse {
  long status = 0;
  std::string body;
  std::map<std::string, std::string> headers;  // response headers, names lower-cased; last value wins

  // The value of header `lowerName`, or "" when absent.
  std::string header(const std::string& lowerName) const;
};

// "host:port" (or "host") of an absolute URL, for error messages; the URL itself when it has no scheme.
std::string serverOf(const std::string& url);

// Performs one POST. Thread-safe (one curl easy handle per call); curl_global_init runs once, on first use.
Result<HttpResponse> httpPost(const HttpRequest& request);

}  // namespace cbtl::textpref
