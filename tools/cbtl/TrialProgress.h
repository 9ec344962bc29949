// TrialProgress.h — the progress line of commands that run many trials (`cbtl sweep`, `cbtl experiment`):
// "[12/50 trials] cbtl seed 3 (4.2 s); elapsed 1:03, ETA 4:12". The ETA is the wall time per trial run here (trials
// finished earlier and read back take none) times the trials left, which counts the jobs in parallel as they ran.
#pragma once

#include <fmt/core.h>

#include <chrono>
#include <cstddef>
#include <string>

namespace cbtl::cli {

// "m:ss", or "h:mm:ss" from an hour on.
inline std::string clockText(double seconds) {
  const auto s = static_cast<long long>(seconds + 0.5);
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

class TrialProgress {
 public:
  // `alreadyDone` of `total` trials finished before this command (a resumed sweep).
  TrialProgress(std::size_t total, std::size_t alreadyDone = 0)
      : total_(total), done_(alreadyDone), start_(std::chrono::steady_clock::now()) {}

  // Counts one more finished trial (`ranHere`: false for one read back from an earlier run) and returns its line.
  std::string finished(const std::string& what, double seconds, bool ranHere = true) {
    ++done_;
    if (ranHere) ++ranHere_;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string eta = "0:00";
    if (done_ < total_)
      eta = ranHere_ == 0 ? std::string("?")
                          : clockText(elapsed / static_cast<double>(ranHere_) * static_cast<double>(total_ - done_));
    return fmt::format("[{}/{} trials] {} ({:.1f} s); elapsed {}, ETA {}", done_, total_, what, seconds,
                       clockText(elapsed), eta);
  }

  std::size_t done() const { return done_; }
  std::size_t total() const { return total_; }

 private:
  std::size_t total_, done_, ranHere_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cbtl::cli
