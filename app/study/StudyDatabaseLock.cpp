#include "app/study/StudyDatabaseLock.h"

#include "app/study/StudyRecords.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace cbtl::app::study {

StudyDatabaseLock::StudyDatabaseLock(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw StudyError(fmt::format("{}: cannot open the study database ({})", path, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw StudyError(fmt::format(
          "{}: another study server is using this database; one database is served by one server at a time (stop "
          "the other, or give this one its own --db)",
          path));
    throw StudyError(fmt::format("{}: cannot lock the study database ({})", path, std::strerror(error)));
  }
}

StudyDatabaseLock::~StudyDatabaseLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace cbtl::app::study
