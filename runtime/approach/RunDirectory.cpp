#include "runtime/approach/RunDirectory.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace cbtl::approach {

namespace fs = std::filesystem;

namespace {

const char* const kTopFiles[] = {"config.json",     "train.csv",    "eval.csv", "world-calls.jsonl", "motions.jsonl.gz",
                                 "checkpoint.json", "profile.json", "llm.json", "timing.json",       "complete.json"};

bool allDigits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// "<name>.tmp.<pid>.<n>" -> "<name>"; otherwise the name unchanged.
std::string withoutTempSuffix(const std::string& name) {
  const auto at = name.rfind(".tmp.");
  if (at == std::string::npos) return name;
  const std::string rest = name.substr(at + 5);
  const auto dot = rest.find('.');
  if (dot == std::string::npos || !allDigits(rest.substr(0, dot)) || !allDigits(rest.substr(dot + 1))) return name;
  return name.substr(0, at);
}

std::string errnoText(int e) { return std::strerror(e); }

// The injected failure of CBTL_TEST_WRITE_FAILS for this file name.
bool writeFailsFor(const std::string& path) {
  const char* name = std::getenv("CBTL_TEST_WRITE_FAILS");
  if (name == nullptr || *name == '\0') return false;
  return withoutTempSuffix(fs::path(path).filename().string()) == name;
}

// Writes all of [data, data + n) to fd; returns 0 or the errno of the failing write.
int writeAll(int fd, const char* data, std::size_t n, bool injectedFailure) {
  if (injectedFailure && n > 0) return ENOSPC;
  while (n > 0) {
    const ssize_t k = ::write(fd, data, n);
    if (k < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += k;
    n -= static_cast<std::size_t>(k);
  }
  return 0;
}

void syncFolder(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the rename itself is done
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

bool isRunFileName(const std::string& relative) {
  const std::string name = withoutTempSuffix(relative);
  for (const char* f : kTopFiles) {
    if (name == f) return true;
  }
  if (name.rfind("models/", 0) == 0) {
    const std::string file = name.substr(7);
    return file.size() > 5 && file.compare(file.size() - 5, 5, ".json") == 0 &&
           allDigits(file.substr(0, file.size() - 5));
  }
  return false;
}

std::vector<std::string> runFilesIn(const std::string& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& sub : {fs::path(dir), fs::path(dir) / "models"}) {
    if (!fs::is_directory(sub, ec)) continue;
    const std::string prefix = sub == fs::path(dir) ? "" : "models/";
    for (const auto& entry : fs::directory_iterator(sub, ec)) {
      const std::string rel = prefix + entry.path().filename().string();
      if (!entry.is_directory(ec) && isRunFileName(rel)) found.push_back(rel);
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

void removeRunFiles(const std::string& dir) {
  for (const auto& rel : runFilesIn(dir)) {
    std::error_code ec;
    fs::remove(fs::path(dir) / rel, ec);
    if (ec)
      throw RunDirectoryError(fmt::format("cannot remove '{}': {}", (fs::path(dir) / rel).string(), ec.message()));
  }
  std::error_code ec;
  const fs::path models = fs::path(dir) / "models";
  if (fs::is_directory(models, ec) && fs::is_empty(models, ec)) fs::remove(models, ec);
}

void removeTemporaries(const std::string& dir) {
  for (const auto& rel : runFilesIn(dir)) {
    if (withoutTempSuffix(fs::path(rel).filename().string()) == fs::path(rel).filename().string()) continue;
    std::error_code ec;
    fs::remove(fs::path(dir) / rel, ec);
    if (ec)
      throw RunDirectoryError(fmt::format("cannot remove '{}': {}", (fs::path(dir) / rel).string(), ec.message()));
  }
}

std::string refusalMessage(const std::string& dir, const std::vector<std::string>& files) {
  std::string list;
  const std::size_t shown = std::min<std::size_t>(files.size(), 4);
  for (std::size_t i = 0; i < shown; ++i) list += (i ? ", " : "") + files[i];
  if (files.size() > shown) list += fmt::format(" and {} more", files.size() - shown);
  return fmt::format("'{}' already holds a run ({}); pass --force to replace it or --resume to continue it", dir, list);
}

DirectoryLock::DirectoryLock(const std::string& dir) {
  const std::string path = (fs::path(dir) / ".lock").string();
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RunDirectoryError(fmt::format("cannot create the lock file '{}': {}", path, errnoText(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    if (e == EWOULDBLOCK) {
      throw RunDirectoryError(fmt::format(
          "'{}' is in use by another cbtl process (it holds '{}'); wait for it or use another --out", dir, path));
    }
    throw RunDirectoryError(fmt::format("cannot lock '{}': {}", path, errnoText(e)));
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the flock
}

void writeFileAtomic(const std::string& path, const std::string& content) {
  static std::atomic<unsigned> counter{0};
  const std::string tmp = fmt::format("{}.tmp.{}.{}", path, static_cast<long>(::getpid()), counter++);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw RunDirectoryError(fmt::format("cannot write '{}': {}", tmp, errnoText(errno)));
  int e = writeAll(fd, content.data(), content.size(), writeFailsFor(path));
  if (e == 0 && ::fsync(fd) != 0) e = errno;
  if (::close(fd) != 0 && e == 0) e = errno;
  if (e == 0 && ::rename(tmp.c_str(), path.c_str()) != 0) e = errno;
  if (e != 0) {
    ::unlink(tmp.c_str());
    throw RunDirectoryError(fmt::format("cannot write '{}': {}", path, errnoText(e)));
  }
  syncFolder(fs::path(path).parent_path());
}

void AppendFile::open(const std::string& path, std::uint64_t keepBytes) {
  close();
  path_ = path;
  buffer_.clear();
  injectedFailure_ = writeFailsFor(path);
  written_ = keepBytes;
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RunDirectoryError(fmt::format("cannot write '{}': {}", path, errnoText(errno)));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || static_cast<std::uint64_t>(st.st_size) < keepBytes) {
    throw RunDirectoryError(fmt::format(
        "'{}' is shorter than its checkpoint says ({} bytes expected); the run cannot be resumed", path, keepBytes));
  }
  if (!S_ISREG(st.st_mode)) return;  // a device (e.g. /dev/full in tests): nothing to truncate
  if (::ftruncate(fd_, static_cast<off_t>(keepBytes)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(keepBytes), SEEK_SET) < 0) {
    throw RunDirectoryError(fmt::format("cannot truncate '{}': {}", path, errnoText(errno)));
  }
}

AppendFile::~AppendFile() {
  if (fd_ >= 0) ::close(fd_);  // unflushed rows are dropped, as a killed process would drop them
}

void AppendFile::flush() {
  if (fd_ < 0 || buffer_.empty()) return;
  if (const int e = writeAll(fd_, buffer_.data(), buffer_.size(), injectedFailure_); e != 0) {
    throw RunDirectoryError(fmt::format("cannot write '{}': {}", path_, errnoText(e)));
  }
  written_ += buffer_.size();
  buffer_.clear();
}

void AppendFile::sync() {
  flush();
  if (fd_ >= 0 && ::fsync(fd_) != 0)
    throw RunDirectoryError(fmt::format("cannot write '{}': {}", path_, errnoText(errno)));
}

void AppendFile::close() {
  if (fd_ < 0) return;
  sync();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw RunDirectoryError(fmt::format("cannot write '{}': {}", path_, errnoText(errno)));
}

std::function<void(const char*, std::int64_t)> killHookFromEnvironment() {
  const char* value = std::getenv("CBTL_TEST_KILL_AT");
  if (value == nullptr || *value == '\0') return nullptr;
  const std::string text = value;
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || !allDigits(text.substr(colon + 1))) {
    throw RunDirectoryError(fmt::format("CBTL_TEST_KILL_AT wants <point>:<step>, not '{}'", text));
  }
  const std::string point = text.substr(0, colon);
  const std::int64_t step = std::stoll(text.substr(colon + 1));
  return [point, step](const char* at, std::int64_t s) {
    if (s == step && point == at) ::raise(SIGKILL);
  };
}

}  // namespace cbtl::approach
