#include "runtime/sim/ChildProcess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace cbtl::sim {

namespace {

constexpr std::size_t kStderrTailLines = 20;

void closeFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

std::string errnoText(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

}  // namespace

ChildProcess::ChildProcess(const std::string& command, const std::string& workingDirectory, std::string stderrPrefix)
    : stderrPrefix_(std::move(stderrPrefix)) {
  // stdin is a socket so that a write to an exited program fails with EPIPE (MSG_NOSIGNAL) instead of a signal.
  int in[2], out[2], err[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, in) != 0) throw std::runtime_error(errnoText("socketpair"));
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]);
    ::close(in[1]);
    throw std::runtime_error(errnoText("pipe"));
  }
  if (::pipe2(err, O_CLOEXEC) != 0) {
    for (int fd : {in[0], in[1], out[0], out[1]}) ::close(fd);
    throw std::runtime_error(errnoText("pipe"));
  }
  // The child reads in[1]; the child's stdin must not be a half-closed direction: shut the parent's read side.
  ::shutdown(in[0], SHUT_RD);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[1], 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  if (!workingDirectory.empty()) posix_spawn_file_actions_addchdir_np(&actions, workingDirectory.c_str());

  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  // Its own process group, so that stopping it stops what the shell started too; default signal dispositions
  // and an empty mask, whatever this process ignores or blocks.
  sigset_t all, none;
  sigfillset(&all);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&attr, &all);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);

  const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
  const int rc = ::posix_spawn(&pid_, "/bin/sh", &actions, &attr, const_cast<char* const*>(argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  ::close(in[1]);
  ::close(out[1]);
  ::close(err[1]);
  stdinFd_ = in[0];
  stdoutFd_ = out[0];
  stderrFd_ = err[0];
  if (rc != 0) {
    pid_ = -1;
    closeFd(stdinFd_);
    closeFd(stdoutFd_);
    closeFd(stderrFd_);
    throw std::runtime_error(std::string("cannot start '") + command + "'" +
                             (workingDirectory.empty() ? "" : " in '" + workingDirectory + "'") + ": " +
                             std::strerror(rc));
  }
}

ChildProcess::~ChildProcess() {
  stop(1000);
  closeFd(stdoutFd_);
  closeFd(stderrFd_);
}

bool ChildProcess::writeLine(const std::string& line) {
  if (stdinFd_ < 0) return false;
  std::string data = line;
  data.push_back('\n');
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(stdinFd_, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

ChildProcess::ReadOutcome ChildProcess::readLine(std::string& line, int timeoutMs, std::size_t maxLineBytes) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
  char chunk[65536];
  for (;;) {
    if (const auto nl = stdoutBuffer_.find('\n'); nl != std::string::npos) {
      line = stdoutBuffer_.substr(0, nl);
      stdoutBuffer_.erase(0, nl + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return ReadOutcome::Line;
    }
    if (stdoutBuffer_.size() > maxLineBytes) {
      stop(0);
      return ReadOutcome::TooLong;
    }
    if (stdoutFd_ < 0) return ReadOutcome::Closed;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return ReadOutcome::TimedOut;
    pollfd fds[2] = {{stdoutFd_, POLLIN, 0}, {stderrFd_, POLLIN, 0}};
    const int ready = ::poll(fds, stderrFd_ >= 0 ? 2 : 1, static_cast<int>(left));
    if (ready < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(errnoText("poll"));
    }
    if (stderrFd_ >= 0 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) drainStderr(false);
    if ((fds[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
      const ssize_t n = ::read(stdoutFd_, chunk, sizeof chunk);
      if (n > 0) {
        stdoutBuffer_.append(chunk, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        closeFd(stdoutFd_);
        // A last line without its newline is still a line; the next read reports the end.
        if (!stdoutBuffer_.empty()) {
          line = std::move(stdoutBuffer_);
          stdoutBuffer_.clear();
          return ReadOutcome::Line;
        }
        // Its last words on stderr come before the report of its end.
        drainStderrFor(200);
        return ReadOutcome::Closed;
      }
    }
  }
}

void ChildProcess::drainStderr(bool untilEnd) {
  char chunk[8192];
  const ssize_t n = ::read(stderrFd_, chunk, sizeof chunk);
  if (n <= 0) {
    if (n < 0 && errno == EINTR) return;
    closeFd(stderrFd_);
    untilEnd = true;
  } else {
    stderrBuffer_.append(chunk, static_cast<std::size_t>(n));
  }
  std::size_t start = 0;
  for (std::size_t nl; (nl = stderrBuffer_.find('\n', start)) != std::string::npos; start = nl + 1) {
    std::string text = stderrBuffer_.substr(start, nl - start);
    std::fprintf(stderr, "%s%s\n", stderrPrefix_.c_str(), text.c_str());
    stderrLines_.push_back(std::move(text));
    if (stderrLines_.size() > kStderrTailLines) stderrLines_.pop_front();
  }
  stderrBuffer_.erase(0, start);
  if (untilEnd && stderrFd_ < 0 && !stderrBuffer_.empty()) {
    std::fprintf(stderr, "%s%s\n", stderrPrefix_.c_str(), stderrBuffer_.c_str());
    stderrLines_.push_back(std::move(stderrBuffer_));
    if (stderrLines_.size() > kStderrTailLines) stderrLines_.pop_front();
    stderrBuffer_.clear();
  }
  std::fflush(stderr);
}

bool ChildProcess::reap(bool wait) {
  if (reaped_ || pid_ < 0) return true;
  for (;;) {
    const pid_t r = ::waitpid(pid_, &status_, wait ? 0 : WNOHANG);
    if (r == pid_) {
      reaped_ = true;
      return true;
    }
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {  // not our child any more (someone reaped it): nothing left to wait for
      reaped_ = true;
      status_ = 0;
      return true;
    }
    return false;
  }
}

void ChildProcess::stop(int graceMs) {
  closeFd(stdinFd_);
  if (pid_ < 0) return;
  if (reaped_) {
    drainStderrFor(50);
    return;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(graceMs);
  while (!reap(false)) {
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(-pid_, SIGKILL);
      ::kill(pid_, SIGKILL);
      reap(true);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  // Whatever it wrote on stderr before it ended is part of its story.
  drainStderrFor(50);
}

void ChildProcess::drainStderrFor(int ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (stderrFd_ >= 0) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    pollfd fd{stderrFd_, POLLIN, 0};
    if (left <= 0 || ::poll(&fd, 1, static_cast<int>(left)) <= 0) break;
    drainStderr(true);
  }
}

std::string ChildProcess::exitDescription() {
  if (!reap(false)) {
    // The program closed its output but has not ended: give it a moment before calling it still running.
    for (int i = 0; i < 100 && !reap(false); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (!reaped_) return "is still running";
  }
  if (WIFEXITED(status_)) return "exited with status " + std::to_string(WEXITSTATUS(status_));
  if (WIFSIGNALED(status_))
    return "was killed by signal " + std::to_string(WTERMSIG(status_)) + " (" + ::strsignal(WTERMSIG(status_)) + ")";
  return "ended";
}

std::string ChildProcess::stderrTail() const {
  std::string out;
  for (const auto& l : stderrLines_) out += "  | " + l + "\n";
  return out;
}

}  // namespace cbtl::sim
