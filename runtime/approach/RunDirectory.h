// RunDirectory.h — the files of a run directory (`cbtl run --out DIR`, one trial of `cbtl experiment`), written so
// that results are never lost or mixed: an existing run is refused unless the caller asks to replace it (Force)
// or to continue it (Resume); one process at a time holds the directory (a lock); every file is written either
// atomically (a temporary file of its own, fsync, rename) or append-only with every flush checked; a write that
// fails (disk full) throws RunDirectoryError naming the file.
//
// The files a run writes (runFileNames(); `--force` removes exactly these and nothing else in DIR):
//   config.json        the options (written at the start; `--resume` compares against it)
//   train.csv          one row per training step (appended; flushed and fsynced at every checkpoint)
//   eval.csv           one row per checkpoint (likewise)
//   models/<step>.json the profile learned by each checkpoint (atomic)
//   world-calls.jsonl  the training world's calls (append-only), replayed by `--resume` (Checkpoint.h)
//   motions.jsonl.gz   what the robot did, training and evaluation (gzip, one member per checkpoint, appended; kept
//                      after completion; only for domains that report motions): JSON lines, one per executed
//                      motion, {"phase": "train" | "eval", "step", "task" (eval), "call": the action, "motion":
//                      the domain's record} — robot domains: robot/world/MotionRecord.h; `cbtl audit` re-checks it.
//                      Programs with a world also mark each accepted plan before its motions, {"phase", "step",
//                      "task" (eval), "plan": {"calls": [names], "dry_run": whether a dry run accepted it}}, and
//                      each time the robot is put back without a motion, {"phase", "step", "task" (eval), "reset":
//                      "episode" | "caregiver"}
//   checkpoint.json    the last complete checkpoint (atomic; written after the files above are durable)
//   profile.json       the final profile (atomic)
//   llm.json           the text backend and its failure counts (atomic, at the end; textpref/RunReport.h)
//   timing.json        the run's wall-clock seconds over every resumed part (atomic, just before complete.json):
//                      not a result (it differs between identical runs), so that `experiment --resume` reports
//                      the time of trials finished earlier
//   complete.json      the completion marker, written last (atomic), with the run's summary
//   *.tmp.<pid>.<n>    temporaries of the atomic writes (left only by a killed process)
// plus DIR/.lock, the lock file, which stays (it is empty and harmless; removing it while others wait would break
// the lock). Other files and folders in DIR are never touched.
//
// Test hooks (environment, read by the CLI and by AppendFile/writeFileAtomic):
//   CBTL_TEST_WRITE_FAILS=<file name>  every write to a file of that name (e.g. "train.csv") fails with ENOSPC.
//   CBTL_TEST_KILL_AT=<point>:<step>   the process sends itself SIGKILL at that point of the loop (see
//                                      ExperimentConfig::testHook for the points).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::approach {

struct RunDirectoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What to do with a directory that already holds a run.
enum class RunMode {
  Fresh,   // refuse it (RunDirectoryError naming DIR, the files found, and --force / --resume)
  Force,   // remove the run's files first (runFileNames() only), then start afresh
  Resume,  // continue from its last complete checkpoint (Checkpoint.h); a complete run is left as it is
};

// The names (relative to DIR, '/'-separated) of the files a run writes, as listed above.
bool isRunFileName(const std::string& relative);
// The run files present in `dir`, sorted; empty when `dir` does not exist.
std::vector<std::string> runFilesIn(const std::string& dir);
// Removes the run files present in `dir` (and `models/` when that leaves it empty). Throws RunDirectoryError.
void removeRunFiles(const std::string& dir);
// Removes the temporaries of atomic writes (`*.tmp.<pid>.<n>`) that a killed process left in `dir` or its
// models/: a resumed run ends with the files of an uninterrupted one. Throws RunDirectoryError.
void removeTemporaries(const std::string& dir);
// The refusal: "'DIR' already holds a run (FILES); pass --force to replace it or --resume to continue it".
std::string refusalMessage(const std::string& dir, const std::vector<std::string>& files);

// An exclusive flock(2) on DIR/.lock, held until destruction (the kernel drops it when the process dies, so a
// killed run never leaves a stale lock). Throws RunDirectoryError when another process holds it.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::string& dir);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

// Writes `content` to `path` atomically: a temporary `path.tmp.<pid>.<n>` (unique per process and call), fsync,
// rename over `path`, fsync of the folder. Readers see the old file or the new one, never a part. Throws
// RunDirectoryError naming the file when any step fails (the temporary is removed).
void writeFileAtomic(const std::string& path, const std::string& content);

// A file written by appending: rows are buffered in memory and written by flush(), whose every write(2) is
// checked; sync() flushes and fsyncs. size() is the file's length including what is still buffered.
// Errors throw RunDirectoryError naming the file.
class AppendFile {
 public:
  AppendFile() = default;
  // Opens `path` for appending after truncating it to `keepBytes` (0: an empty file); creates it when missing.
  // Throws when the file is shorter than keepBytes (it cannot hold the checkpointed rows).
  void open(const std::string& path, std::uint64_t keepBytes = 0);
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  bool isOpen() const { return fd_ >= 0; }
  void append(const std::string& text) { buffer_ += text; }
  void flush();
  void sync();
  void close();  // flush, fsync and close; errors throw
  std::uint64_t size() const { return written_ + buffer_.size(); }
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_, buffer_;
  std::uint64_t written_ = 0;
  bool injectedFailure_ = false;
};

// The CBTL_TEST_KILL_AT hook (null when the variable is unset): called as hook(point, step), it raises SIGKILL
// when point and step match. Throws RunDirectoryError for a malformed value.
std::function<void(const char*, std::int64_t)> killHookFromEnvironment();

}  // namespace cbtl::approach
