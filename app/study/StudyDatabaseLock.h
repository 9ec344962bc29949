// StudyDatabaseLock.h — one study server per database. Two servers on one file once gave two participants the same
// seed (each numbered participants from its own count) and a participant served by both a 500 on every page (each
// held its own session). The lock is an exclusive flock(2) on the database file, held while the server runs and
// dropped by the kernel when the process ends, however it ends (no stale lock file after a kill -9). flock locks
// are apart from the POSIX locks SQLite takes, so readers (`cbtl study analyze`, `cbtl profile`) are not affected.
#pragma once

#include <string>

namespace cbtl::app::study {

class StudyDatabaseLock {
 public:
  // Takes the lock on the existing file `path`. Throws StudyError when another process holds it or the file cannot
  // be opened.
  explicit StudyDatabaseLock(const std::string& path);
  ~StudyDatabaseLock();
  StudyDatabaseLock(const StudyDatabaseLock&) = delete;
  StudyDatabaseLock& operator=(const StudyDatabaseLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace cbtl::app::study
