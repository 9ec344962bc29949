// AdmissionLimit.h — how fast, and how many, new participants a study server admits, so that nobody can fill the
// study database from a script (20,000 participants in 60 s were once created) or find participant ids by trying
// them (every begin without a key, new id or not, is counted).
//
// A token bucket: `perMinute` admissions a minute on average, up to `burst` at once; beyond, the caller is told
// how many whole seconds until the next one (an HTTP Retry-After). `total` bounds the participants the study
// holds; 0 for either means no limit. The bucket is the server's, not a client's: behind a reverse proxy every
// participant comes from one address. Thread-safe. Times are std::chrono::steady_clock's, passed in for tests.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>

namespace cbtl::app::study {

struct AdmissionOptions {
  double perMinute = 120;     // new participants a minute, on average (0: no limit)
  double burst = 60;          // at most this many at once
  std::int64_t total = 1000;  // participants the study holds at most (0: no limit)
};

class AdmissionLimit {
 public:
  enum class Verdict { Admitted, TooFast, Full };
  struct Decision {
    Verdict verdict = Verdict::Admitted;
    int retryAfterSeconds = 0;  // TooFast: when to try again, >= 1
  };

  explicit AdmissionLimit(AdmissionOptions options);

  // Takes one admission at `now` for a study that holds `participants` already. Full takes none.
  Decision admit(std::chrono::steady_clock::time_point now, std::int64_t participants);
  const AdmissionOptions& options() const { return options_; }

 private:
  AdmissionOptions options_;
  std::mutex mutex_;
  double tokens_;
  std::chrono::steady_clock::time_point last_{};
  bool started_ = false;
};

}  // namespace cbtl::app::study
